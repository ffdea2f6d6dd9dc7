"""Blender's evaluated depsgraph as a glint scene dict (docs/blender.md says what maps).

Everything is read in memory: meshes through numpy (foreach_get), handed to glint.load_dict
without text or temporary files. What does not map is collected in `Export.unmapped`, one line
per kind of thing, for the engine to report once per render.

Frames: Blender is right-handed with z up, glint left-handed with y up. Every world point p goes
to W p with W = [[0, 1, 0], [0, 0, 1], [-1, 0, 0]] (glint x = Blender y, y = z, z = -x): a mirror,
so handedness turns with it and the picture does not, and the turn about the up axis makes an
equirectangular world texture land where Blender puts it (glint's map centre looks along +z, i.e.
Blender's -x, the centre of Blender's map).
"""
import math

import numpy as np

W = np.array([[0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [-1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]])

# Principled BSDF inputs glint maps (Blender 3.4's names); the others are reported when they
# differ from their defaults.
_MAPPED = {"Base Color", "Metallic", "Roughness", "IOR", "Transmission", "Emission", "Emission Strength", "Alpha",
           "Clearcoat", "Clearcoat Roughness", "Sheen", "Sheen Tint", "Specular"}
_IGNORED = {"Normal", "Clearcoat Normal", "Tangent", "Weight"}
_VISIBLE_LIGHTS = ("area lights and point lights with a radius are shapes the camera sees in glint "
                   "(Cycles hides light objects from camera rays)")


def _matrix(m):
    return np.array([list(row) for row in m], dtype=np.float64)


def _point(m, p=(0.0, 0.0, 0.0)):
    q = W @ _matrix(m) @ np.array([*p, 1.0])
    return [float(q[0]), float(q[1]), float(q[2])]


def _vector(m, v):
    q = W[:3, :3] @ _matrix(m)[:3, :3] @ np.array(v, dtype=np.float64)
    return [float(x) for x in q]


def _rgb(c, scale=1.0):
    return [float(c[0]) * scale, float(c[1]) * scale, float(c[2]) * scale]


def viewport_view(region_data, clip_end=1000.0):
    """What a 3D viewport shows, as (camera-to-world matrix, vertical field of view in degrees or
    None, orthographic height or None), from its view and projection matrices: the vertical field
    is 2 atan(1 / P[1][1]) (perspective), the height 2 / P[1][1] (orthographic). An orthographic
    viewport also sees what lies behind its eye, so the camera is moved back by half the clip range."""
    to_world = region_data.view_matrix.inverted()
    p11 = float(region_data.window_matrix[1][1])
    if region_data.is_perspective:
        return to_world, math.degrees(2 * math.atan(1 / p11)), None
    back = to_world.copy()
    back.translation = to_world.translation + to_world.to_3x3() @ type(to_world.translation)((0, 0, clip_end / 2))
    return back, None, 2 / p11


class Export:
    def __init__(self, depsgraph, width, height, view=None):
        """`view`: a viewport's viewport_view() to render instead of the scene's camera."""
        self.depsgraph = depsgraph
        self.scene = depsgraph.scene
        self.width, self.height = width, height
        self.view = view
        self.unmapped = []
        self._meshes = {}       # evaluated object name -> [(arrays, material slot)]
        self._materials = {}    # material name -> glint material dict
        self._volumes = {}      # material name -> glint medium name, or None (no volume)
        self._media = {}        # glint medium name -> medium dict
        self._images = {}       # image name -> linear RGB pixels (numpy), or None

    def note(self, text):
        if text not in self.unmapped:
            self.unmapped.append(text)

    # --- the scene -------------------------------------------------------------------------------

    def scene_dict(self, spp, max_depth):
        objects, lights = [], []
        for inst in self.depsgraph.object_instances:
            obj = inst.object
            matrix = inst.matrix_world.copy()
            if obj.type == "MESH" or (obj.type in {"CURVE", "SURFACE", "META", "FONT"}):
                objects += self.mesh_objects(obj, matrix)
            elif obj.type == "LIGHT":
                self.light(obj, matrix, objects, lights)
            elif obj.type == "VOLUME":
                objects += self.volume_object(obj, matrix)
            elif obj.type not in {"CAMERA", "EMPTY", "ARMATURE", "LATTICE", "SPEAKER", "LIGHT_PROBE"}:
                self.note(f"object '{obj.name}' of type {obj.type}: not mapped")
        scene = {
            "camera": self.camera(),
            "film": {"width": self.width, "height": self.height, "filter": {"type": "box"}},
            "sampler": {"spp": spp},
            "integrator": {"type": "path", "max_depth": max_depth},
            "background": self.world(),
            "objects": objects,
        }
        if lights:
            scene["lights"] = lights
        if self._media:
            scene["media"] = self._media
        return scene

    # --- camera ----------------------------------------------------------------------------------

    def camera(self):
        if self.view is not None:
            m, fov, height = self.view
            forward = _vector(m, (0, 0, -1))
            c = {"type": "look_at", "from": _point(m), "to": [a + b for a, b in zip(_point(m), forward)],
                 "up": _vector(m, (0, 1, 0))}
            if fov is not None:
                c["fov"] = fov
            else:
                c["projection"], c["height"] = "orthographic", height
            return c
        cam = self.scene.camera
        if cam is None:
            raise ValueError("the scene has no camera")
        data = cam.data
        m = cam.matrix_world
        forward = _vector(m, (0, 0, -1))
        c = {"type": "look_at", "from": _point(m), "to": [a + b for a, b in zip(_point(m), forward)],
             "up": _vector(m, (0, 1, 0))}
        aspect = self.width / self.height
        fit = data.sensor_fit
        horizontal = fit == "HORIZONTAL" or (fit == "AUTO" and self.width >= self.height)
        if data.type == "ORTHO":
            c["projection"] = "orthographic"
            c["height"] = data.ortho_scale / aspect if horizontal else data.ortho_scale
        elif data.type == "PERSP":
            sensor = data.sensor_width if (fit != "VERTICAL") else data.sensor_height
            half = sensor / (2 * data.lens)  # tan of half the field along the fitted side
            vertical = half / aspect if horizontal else half
            c["fov"] = math.degrees(2 * math.atan(vertical))
        else:
            self.note(f"camera '{cam.name}': panoramic cameras are not mapped (rendered as perspective)")
            c["fov"] = 40
        if data.shift_x or data.shift_y:
            self.note(f"camera '{cam.name}': lens shift is not mapped")
        if data.dof.use_dof and data.type == "PERSP":
            if data.dof.focus_object is not None:
                focus = (data.dof.focus_object.matrix_world.translation - m.translation).length
            else:
                focus = data.dof.focus_distance
            c["aperture_radius"] = data.lens / 1000 / (2 * data.dof.aperture_fstop)
            c["focus_distance"] = max(focus, 1e-4)
        return c

    # --- world -----------------------------------------------------------------------------------

    def world(self):
        world = self.scene.world
        if world is None:
            return {"type": "constant", "color": [0, 0, 0]}
        if not world.use_nodes or world.node_tree is None:
            return {"type": "constant", "color": _rgb(world.color)}
        out = next((n for n in world.node_tree.nodes if n.type == "OUTPUT_WORLD" and n.is_active_output), None)
        if out is not None and out.inputs["Volume"].is_linked:
            self.note("world: a world volume (fog everywhere) is not mapped")
        link = out.inputs["Surface"].links[0] if out and out.inputs["Surface"].is_linked else None
        if link is None:
            return {"type": "constant", "color": [0, 0, 0]}
        node = link.from_node
        if node.type != "BACKGROUND":
            self.note(f"world: surface node {node.bl_idname} is not mapped (black)")
            return {"type": "constant", "color": [0, 0, 0]}
        strength = float(node.inputs["Strength"].default_value)
        color = node.inputs["Color"]
        if color.is_linked:
            src = color.links[0].from_node
            if src.type == "TEX_ENVIRONMENT" and src.image is not None and src.image.filepath:
                if src.projection != "EQUIRECTANGULAR":
                    self.note("world: environment textures other than equirectangular are not mapped")
                if src.inputs["Vector"].is_linked:
                    self.note("world: a mapped vector into the environment texture is not applied")
                return {"type": "environment", "filename": _image_path(src.image), "scale": strength}
            self.note(f"world: colour from node {src.bl_idname} is not mapped (its default is used)")
        return {"type": "constant", "color": _rgb(color.default_value, strength)}

    # --- lights ----------------------------------------------------------------------------------

    def light(self, obj, m, objects, lights):
        light = obj.data
        color = _rgb(light.color)
        if light.use_nodes:
            self.note(f"light '{obj.name}': light node trees are not mapped")
        if light.type == "SUN":
            lights.append({"type": "directional", "direction": _vector(m, (0, 0, -1)),
                           "intensity": _rgb(color, light.energy),
                           "angular_diameter": min(179.0, math.degrees(light.angle))})
            return
        # Cycles: a point or spot light of power P has intensity P / (4 pi) (W/sr).
        intensity = _rgb(color, light.energy / (4 * math.pi))
        if light.type == "POINT":
            if light.shadow_soft_size > 0:
                # A sphere of radius r seen as a disk of radiance I / (pi r^2), as Cycles has it.
                r = light.shadow_soft_size * _uniform_scale(m)
                self.note(_VISIBLE_LIGHTS)
                objects.append({"type": "sphere", "center": _point(m), "radius": r,
                                "material": {"type": "diffuse", "albedo": [0, 0, 0],
                                             "emission": _rgb(intensity, 1 / (math.pi * r * r))}})
            else:
                lights.append({"type": "point", "position": _point(m), "intensity": intensity})
        elif light.type == "SPOT":
            half = math.degrees(light.spot_size / 2)
            lights.append({"type": "spot", "position": _point(m), "direction": _vector(m, (0, 0, -1)),
                           "intensity": intensity, "cone_angle": half,
                           "falloff_start": half * (1 - light.spot_blend)})
            if light.shadow_soft_size > 0:
                self.note("spot lights: the radius (soft shadows) is not mapped")
        elif light.type == "AREA":
            sx = light.size
            sy = light.size_y if light.shape in {"RECTANGLE", "ELLIPSE"} else light.size
            e1, e2 = _vector(m, (sx, 0, 0)), _vector(m, (0, sy, 0))
            area = float(np.linalg.norm(np.cross(e1, e2)))
            round_ = light.shape in {"DISK", "ELLIPSE"}
            if round_:
                area *= math.pi / 4
            # Cycles: an area light of power P has radiance P / (4 A), on its -z side.
            radiance = _rgb(color, light.energy / (4 * area))
            material = {"type": "diffuse", "albedo": [0, 0, 0], "emission": radiance}
            if round_:
                if light.shape == "ELLIPSE" and abs(sx - sy) > 1e-6 * max(sx, sy):
                    self.note("area lights: ellipses are rendered as disks of the same area")
                objects.append({"type": "disk", "center": _point(m), "normal": _vector(m, (0, 0, -1)),
                                "radius": math.sqrt(area / math.pi), "material": material})
            else:
                corner = _point(m, (-sx / 2, -sy / 2, 0))
                # glint's quad faces along edge1 x edge2; through the mirror W, (W e1) x (W e2) is
                # -W (e1 x e2) = W (-z): the light's side, as Blender has it.
                objects.append({"type": "quad", "corner": corner, "edge1": e1, "edge2": e2, "material": material})
            self.note(_VISIBLE_LIGHTS)
            if light.spread < math.pi - 1e-3:
                self.note("area lights: spread is not mapped (light leaves in every direction)")
        else:
            self.note(f"light '{obj.name}' of type {light.type}: not mapped")

    # --- meshes ----------------------------------------------------------------------------------

    def mesh_objects(self, obj, matrix):
        parts = self._meshes.get(obj.name)
        if parts is None:
            parts = self._meshes[obj.name] = self.mesh_parts(obj)
        m = W @ _matrix(matrix)
        transform = [{"matrix": [[float(x) for x in row] for row in m[:3]]}]
        out = []
        for arrays, slot in parts:
            material, alpha = self.material(obj, slot)
            o = dict(arrays, type="mesh", material=material, transform=transform)
            if alpha is not None:
                o["alpha"], o["alpha_mode"] = alpha, "blend"
            mat = obj.material_slots[slot].material if slot < len(obj.material_slots) else None
            medium = self.mesh_medium(mat)
            if medium is not None:
                # The mesh bounds the medium (its normals face out of it); with no surface shader
                # it is only the medium's boundary, as in Cycles.
                o["interior"] = medium
                if not self._has_surface(mat):
                    o["material"] = "interface"
                    o.pop("alpha", None), o.pop("alpha_mode", None)
            out.append(o)
        return out

    # --- volumes ---------------------------------------------------------------------------------

    @staticmethod
    def _output(mat):
        if mat is None or not mat.use_nodes or mat.node_tree is None:
            return None
        return next((n for n in mat.node_tree.nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output), None)

    def _has_surface(self, mat):
        out = self._output(mat)
        return out is not None and out.inputs["Surface"].is_linked

    def volume_node(self, mat):
        out = self._output(mat)
        if out is None or not out.inputs["Volume"].is_linked:
            return None
        return out.inputs["Volume"].links[0].from_node

    def coefficients(self, mat, node):
        """Cycles' volume closures as glint's sigma_a, sigma_s (per metre), g, and the emission
        per metre (Cycles' volume emission is radiance added per unit length, not scaled by
        density). Principled Volume, as Cycles computes it: sigma_s = D C and
        sigma_a = D max(1 - C, 0) max(1 - sqrt(A), 0) (A: Absorption Color)."""
        i = node.inputs
        value = (lambda name: self.number_input(mat, i[name]))
        color = (lambda name: self.color_value(mat, i[name]))
        zero = [0.0, 0.0, 0.0]
        if node.type == "PRINCIPLED_VOLUME":
            d = max(0.0, value("Density"))
            c = color("Color")
            a = color("Absorption Color")
            sigma_s = [d * x for x in c]
            sigma_a = [d * max(1 - x, 0.0) * max(1 - math.sqrt(max(y, 0.0)), 0.0) for x, y in zip(c, a)]
            strength = max(0.0, value("Emission Strength"))
            emission = [strength * x for x in color("Emission Color")]
            if value("Blackbody Intensity") > 1e-3:
                self.note(f"material '{mat.name}': Principled Volume blackbody emission is not mapped")
            return sigma_a, sigma_s, value("Anisotropy"), emission
        if node.type == "VOLUME_ABSORPTION":
            d = max(0.0, value("Density"))
            return [d * max(1 - x, 0.0) for x in color("Color")], zero, 0.0, zero
        if node.type == "VOLUME_SCATTER":
            d = max(0.0, value("Density"))
            return zero, [d * x for x in color("Color")], value("Anisotropy"), zero
        self.note(f"material '{mat.name}': volume node {node.bl_idname} is not mapped (no medium)")
        return None

    def _medium_name(self, mat):
        return f"volume '{mat.name}'"

    def mesh_medium(self, mat):
        """The glint medium a mesh with this material encloses (homogeneous), or None."""
        if mat is None:
            return None
        if mat.name in self._volumes:
            return self._volumes[mat.name]
        name = None
        node = self.volume_node(mat)
        got = self.coefficients(mat, node) if node is not None else None
        if got is not None:
            sigma_a, sigma_s, g, emission = got
            medium = {"type": "homogeneous", "sigma_a": sigma_a, "sigma_s": sigma_s,
                      "g": min(0.99, max(-0.99, g))}
            if any(emission):
                # glint's media emit sigma_a Le per unit length (pbrt's convention).
                if all(e == 0 or a > 0 for e, a in zip(emission, sigma_a)):
                    medium["emission"] = [e / a if e > 0 else 0.0 for e, a in zip(emission, sigma_a)]
                else:
                    self.note(f"material '{mat.name}': volume emission where nothing absorbs is not mapped")
            name = self._medium_name(mat)
            self._media[name] = medium
        self._volumes[mat.name] = name
        return name

    def volume_object(self, obj, matrix):
        """An OpenVDB Volume object: a grid medium read from its file (the current frame's), placed
        by the grid's own transform and then the object's, inside an interface box around its
        bounds. The material's volume node gives the coefficients at grid value 1; its Density
        Attribute names the grid."""
        import bpy
        vol = obj.data
        path = getattr(vol.grids, "frame_filepath", "") or vol.filepath
        if not path:
            self.note(f"volume object '{obj.name}': only volumes read from OpenVDB files are mapped")
            return []
        path = bpy.path.abspath(path, library=vol.library)
        mat = obj.material_slots[0].material if len(obj.material_slots) else None
        node = self.volume_node(mat)
        got = self.coefficients(mat, node) if node is not None else None
        if got is None:
            if node is None:
                self.note(f"volume object '{obj.name}': no volume shader, nothing to render")
            return []
        sigma_a, sigma_s, g, emission = got
        grid = "density"
        if node.type == "PRINCIPLED_VOLUME":
            grid = node.inputs["Density Attribute"].default_value or "density"
            if any(emission):
                self.note(f"material '{mat.name}': Principled Volume emission on volume objects is not mapped")
            try:
                vol.grids.load()
                names = {gr.name for gr in vol.grids}
            except Exception:  # a file Blender cannot read: glint's reader says what is wrong
                names = set()
            attr = node.inputs["Color Attribute"].default_value
            if attr and attr in names:
                self.note(f"material '{mat.name}': the colour grid '{attr}' is not mapped (Color is used)")
        render = getattr(vol, "render", None)
        if render is None or render.space == "OBJECT":
            # Blender's default: the density is per unit of the object's own space, so a volume
            # scaled by s has s times fewer of them per metre along a ray (glint's are per metre).
            k = 1 / max(_uniform_scale(matrix), 1e-12)
            s = matrix.to_scale()
            if max(abs(x) for x in s) > 1.001 * min(abs(x) for x in s):
                self.note(f"volume object '{obj.name}': object-space density under a non-uniform scale "
                          "is mapped by the mean scale")
            sigma_a, sigma_s = [k * x for x in sigma_a], [k * x for x in sigma_s]
        m = W @ _matrix(matrix)
        rows = [[float(x) for x in row] for row in m[:3]]
        name = f"volume object '{obj.name}'"
        self._media[name] = {"type": "grid", "file": path, "grid": grid, "sigma_a": sigma_a,
                             "sigma_s": sigma_s, "g": min(0.99, max(-0.99, g)),
                             "transform": [{"matrix": rows}]}
        corners = np.array([list(c) for c in obj.bound_box], dtype=np.float64)
        lo, hi = corners.min(axis=0), corners.max(axis=0)
        pad = 0.02 * (hi - lo).max() + 1e-6  # the trilinear support reaches past the active voxels
        return [{"type": "box", "min": [float(x) for x in lo - pad], "max": [float(x) for x in hi + pad],
                 "material": "interface", "interior": name, "transform": [{"matrix": rows}]}]

    def mesh_parts(self, obj):
        """The object's evaluated mesh (modifiers applied), split by material slot, as numpy arrays:
        one vertex per triangle corner (split normals, UVs and colours live on corners)."""
        try:
            mesh = obj.to_mesh()
        except RuntimeError:
            return []
        if mesh is None:
            return []
        try:
            mesh.calc_loop_triangles()
            if hasattr(mesh, "calc_normals_split"):
                mesh.calc_normals_split()
            nt = len(mesh.loop_triangles)
            if nt == 0:
                return []
            loops = np.empty(nt * 3, np.int32)
            mesh.loop_triangles.foreach_get("loops", loops)
            tri_material = np.empty(nt, np.int32)
            mesh.loop_triangles.foreach_get("material_index", tri_material)
            co = np.empty(len(mesh.vertices) * 3, np.float32)
            mesh.vertices.foreach_get("co", co)
            loop_vertex = np.empty(len(mesh.loops), np.int32)
            mesh.loops.foreach_get("vertex_index", loop_vertex)
            normal = np.empty(len(mesh.loops) * 3, np.float32)
            mesh.loops.foreach_get("normal", normal)
            corner = {"positions": co.reshape(-1, 3)[loop_vertex[loops]],
                      "normals": normal.reshape(-1, 3)[loops]}
            if mesh.uv_layers.active is not None:
                uv = np.empty(len(mesh.loops) * 2, np.float32)
                mesh.uv_layers.active.data.foreach_get("uv", uv)
                corner["uvs"] = uv.reshape(-1, 2)[loops]
            colors = getattr(mesh, "color_attributes", None)
            active = colors.active_color if colors is not None else None
            if active is not None and active.data_type in {"FLOAT_COLOR", "BYTE_COLOR"}:
                rgba = np.empty(len(active.data) * 4, np.float32)
                active.data.foreach_get("color", rgba)
                rgba = rgba.reshape(-1, 4)
                at = loops if active.domain == "CORNER" else loop_vertex[loops]
                corner["colors"] = np.ascontiguousarray(rgba[at, :3])
            parts = []
            for slot in np.unique(tri_material):
                keep = np.repeat(tri_material == slot, 3)
                arrays = {k: np.ascontiguousarray(v[keep]) for k, v in corner.items()}
                arrays["indices"] = np.arange(len(arrays["positions"]), dtype=np.uint32).reshape(-1, 3)
                parts.append((arrays, int(slot)))
            return parts
        finally:
            obj.to_mesh_clear()

    # --- materials -------------------------------------------------------------------------------

    def material(self, obj, slot):
        """The glint material of the object's slot, and its alpha (None when opaque)."""
        mat = obj.material_slots[slot].material if slot < len(obj.material_slots) else None
        if mat is None:
            return {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]}, None
        if mat.name not in self._materials:
            self._materials[mat.name] = self.convert_material(mat)
        return self._materials[mat.name]

    def convert_material(self, mat):
        if not mat.use_nodes or mat.node_tree is None:
            return {"type": "diffuse", "albedo": _rgb(mat.diffuse_color)}, None
        out = self._output(mat)
        if out is None or not out.inputs["Surface"].is_linked:
            return {"type": "diffuse", "albedo": [0, 0, 0]}, None
        node = out.inputs["Surface"].links[0].from_node
        if node.type == "BSDF_PRINCIPLED":
            return self.principled(mat, node)
        if node.type == "BSDF_DIFFUSE":
            if self.number_input(mat, node.inputs["Roughness"]) > 0:
                self.note(f"material '{mat.name}': Diffuse BSDF roughness (Oren-Nayar) is not mapped (Lambertian)")
            return {"type": "diffuse", "albedo": self.color_input(mat, node.inputs["Color"])}, None
        if node.type == "EMISSION":
            e = _rgb(node.inputs["Color"].default_value, float(node.inputs["Strength"].default_value))
            return {"type": "diffuse", "albedo": [0, 0, 0], "emission": e}, None
        self.note(f"material '{mat.name}': surface node {node.bl_idname} is not mapped (grey diffuse)")
        return {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]}, None

    def principled(self, mat, node):
        i = node.inputs
        value = (lambda name: self.number_input(mat, i[name]))
        base = self.color_input(mat, i["Base Color"])
        m = {"type": "pbr", "base_color": base, "metallic": value("Metallic"),
             "roughness": value("Roughness"), "ior": max(1.0001, value("IOR")),
             "transmission": value("Transmission")}
        spec = value("Specular")
        if m["metallic"] == 0 and m["transmission"] == 0 and spec > 0:
            # Principled (v1) adds its specular layer over an undimmed diffuse; glint's pbr puts the
            # diffuse under a dielectric coat, whose internal reflection leaves the albedo
            # rho (1 - Fdr) / (1 - rho Fdr) (Fdr: the coat's diffuse reflectance from inside).
            # The base colour is the one whose coated albedo is Principled's: for a value, and
            # texel by texel for an image (whose linear pixels are at hand).
            fdr = _fdr_inside(m["ior"])
            if isinstance(base, list):
                m["base_color"] = [c / ((1 - fdr) + c * fdr) if c > 0 else 0.0 for c in base]
            elif "pixels" in base:
                p = base["pixels"]
                m["base_color"] = dict(base, pixels=(p / ((1 - fdr) + p * fdr)).astype(np.float32))
        if value("Clearcoat") > 0:
            m["clearcoat"] = value("Clearcoat")
            m["clearcoat_roughness"] = value("Clearcoat Roughness")
        if value("Sheen") > 0:
            tint = value("Sheen Tint")
            b = base if isinstance(base, list) else [1.0, 1.0, 1.0]
            m["sheen"] = [value("Sheen") * ((1 - tint) + tint * c) for c in b]
        # Blender's Specular 0.5 is an F0 of 0.04 (index 1.5): glTF's specular weight is twice it.
        m["specular"] = min(1.0, 2 * spec)
        if spec == 0 and m["metallic"] == 0 and m["transmission"] == 0 and "clearcoat" not in m and "sheen" not in m:
            # No specular layer at all: a diffuse surface (what glint's pbr is at specular 0).
            m = {"type": "diffuse", "albedo": base}
        if 2 * spec > 1:
            self.note(f"material '{mat.name}': Specular above 0.5 is clipped to 0.5")
        strength = value("Emission Strength")
        emission = i["Emission"]
        if strength > 0 and (emission.is_linked or any(emission.default_value[:3])):
            e = self.color_input(mat, emission)
            m["emission"] = ({"type": "scale", "texture": e, "factor": strength} if isinstance(e, dict)
                             else _rgb(e, strength))
        alpha = value("Alpha")
        for name, socket in i.items():
            if name in _MAPPED or name in _IGNORED or not hasattr(socket, "default_value"):
                continue
            if socket.is_linked or _differs_from_default(node, name):
                self.note(f"material '{mat.name}': Principled input '{name}' is not mapped")
        if i["Normal"].is_linked:
            self.normal_map(mat, i["Normal"].links[0].from_node, m)
        return m, ([alpha] * 3 if alpha < 1 else None)

    def normal_map(self, mat, node, m):
        """A Normal Map node (tangent space) fed by an Image Texture: glint's normal_map, the
        node's Strength its normal_scale (both follow glTF's convention, +y along +v)."""
        color = node.inputs["Color"] if node.type == "NORMAL_MAP" else None
        if color is None or node.space != "TANGENT" or not color.is_linked:
            self.note(f"material '{mat.name}': only tangent-space Normal Map nodes fed by an image are mapped")
            return
        texture = self.color_input(mat, color)
        if not isinstance(texture, dict):
            return
        texture["encoding"] = "linear"
        m["normal_map"] = texture
        strength = self.number_input(mat, node.inputs["Strength"])
        if strength != 1:
            m["normal_scale"] = min(100.0, max(0.0, strength))

    def color_input(self, mat, socket):
        if not socket.is_linked:
            return _rgb(socket.default_value)
        src = socket.links[0].from_node
        pixels = self.image_pixels(src.image) if src.type == "TEX_IMAGE" and src.image is not None else None
        if pixels is not None:
            # The texels in memory (packed and generated images too), linear: no file is read.
            t = {"type": "image", "pixels": pixels, "encoding": "linear"}
            if src.extension == "EXTEND":
                t["wrap"] = "clamp"
            if src.inputs["Vector"].is_linked:
                self.note(f"material '{mat.name}': a mapped vector into an image texture is not applied")
            return t
        self.note(f"material '{mat.name}': '{socket.name}' from node {src.bl_idname} is not mapped (its value is used)")
        return _rgb(socket.default_value)

    def image_pixels(self, image):
        """An image's RGB as linear float32 numpy rows from the top, read from Blender's memory
        (each image once a render); None when it has no pixels. Byte images in a colour space other
        than the linear ones are decoded from sRGB (Blender keeps float images linear)."""
        if image.name in self._images:
            return self._images[image.name]
        pixels = None
        w, h = image.size
        if w > 0 and h > 0 and image.channels > 0:
            flat = np.empty(w * h * image.channels, np.float32)
            image.pixels.foreach_get(flat)
            rgb = flat.reshape(h, w, image.channels)[::-1, :, :3]
            if rgb.shape[2] == 1 or image.channels == 2:
                rgb = np.repeat(rgb[:, :, :1], 3, axis=2)
            linear = image.is_float or image.colorspace_settings.name in {"Non-Color", "Linear", "Linear Rec.709"}
            pixels = np.ascontiguousarray(rgb if linear else _srgb_decode(rgb), dtype=np.float32)
            pixels = np.maximum(pixels, 0)  # glint refuses negative texels; Blender allows them
        self._images[image.name] = pixels
        return pixels

    def color_value(self, mat, socket):
        """A colour socket's value (a medium's coefficients take no textures): what feeds it, if
        anything, is reported as number_input reports it."""
        if socket.is_linked:
            self.note(f"material '{mat.name}': '{socket.name}' from node "
                      f"{socket.links[0].from_node.bl_idname} is not mapped (its value is used)")
        return _rgb(socket.default_value)

    def number_input(self, mat, socket):
        if socket.is_linked:
            self.note(f"material '{mat.name}': '{socket.name}' from node "
                      f"{socket.links[0].from_node.bl_idname} is not mapped (its value is used)")
        return float(socket.default_value)


def _fresnel(cos_i, eta):
    """Unpolarised Fresnel reflectance of a dielectric interface (eta: the far side's index over
    the near side's)."""
    sin2_t = (1 - cos_i * cos_i) / (eta * eta)
    if sin2_t >= 1:
        return 1.0
    cos_t = math.sqrt(1 - sin2_t)
    r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    return 0.5 * (r_par * r_par + r_perp * r_perp)


def _fdr_inside(eta, steps=1024):
    """The coat's reflectance, from inside, of diffuse light: 2 int_0^1 F(mu, 1/eta) mu dmu (the
    same integral as glint's diffuse_fresnel_inside)."""
    return sum(2 * _fresnel((i + 0.5) / steps, 1 / eta) * (i + 0.5) / steps / steps for i in range(steps))


def _srgb_decode(c):
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4).astype(np.float32)


def _image_path(image):
    import bpy
    return bpy.path.abspath(image.filepath, library=image.library)


def _uniform_scale(m):
    s = m.to_scale()
    return float(abs(s[0] * s[1] * s[2]) ** (1 / 3))


_DEFAULTS = {}


def _differs_from_default(node, name):
    """Whether a Principled input differs from its value in a fresh node (the defaults are read
    once from a node made for the purpose, so they follow Blender's version)."""
    if not _DEFAULTS:
        import bpy
        tree = bpy.data.node_groups.new("glint-defaults", "ShaderNodeTree")
        try:
            fresh = tree.nodes.new("ShaderNodeBsdfPrincipled")
            for k, s in fresh.inputs.items():
                if hasattr(s, "default_value"):
                    v = s.default_value
                    _DEFAULTS[k] = tuple(v) if hasattr(v, "__len__") else v
        finally:
            bpy.data.node_groups.remove(tree)
    v = node.inputs[name].default_value
    v = tuple(v) if hasattr(v, "__len__") else v
    d = _DEFAULTS.get(name)
    if isinstance(v, tuple):
        return d is None or any(abs(a - b) > 1e-6 for a, b in zip(v, d))
    return d is None or abs(v - d) > 1e-6
