// The article's Figure 14 (scenes/seed/fig14-reflections.yaml) for POV-Ray 3.7, for the
// side-by-side benchmark in bench/compare_povray.sh. Same camera, light, geometry, colours,
// checker and depth; ambient + diffuse with reflection, no specular highlight.
//
// Shading: glint computes (1-s) d + s (d * r) with d = K (a + I cos). POV-Ray's finish adds its
// terms, so the closest equivalent is ambient (1-s) a, diffuse (1-s), and a metallic
// reflection of s (reflection tinted by the pigment K). The images differ only in that POV-Ray
// tints reflections by K where glint tints them by d (K times the lighting).
#version 3.7;
global_settings {
  assumed_gamma 1.0
  ambient_light rgb 1
  max_trace_level 6   // the camera ray plus 5 reflection bounces = glint's max_depth 5
  adc_bailout 0       // trace every reflection to the limit, as glint does
}

// The article's camera: P, V = normalize(0,-0.25,1), viewport 2*16/9 x 2 at z = 1.
// right = w H with H = (1,0,0); up = h U with U = V x H.
camera {
  perspective
  location <0, 1.6, -1.5>
  direction <0, -0.24253562503633297, 0.9701425001453319>
  right <3.5555555555555554, 0, 0>
  up <0, 1.9402850002906638, 0.48507125007266594>
}

// Directional light travelling along (-1,-1,1), intensity 1.
light_source { <1000, 1000, -1000> color rgb 1 parallel point_at <0, 0, 0> }

// The article's sky: t = (y + 1)/2 over ray directions.
sky_sphere {
  pigment {
    gradient y
    color_map { [0.0 rgb <1, 1, 1>] [1.0 rgb <0.5, 0.7, 1.0>] }
    scale 2 translate -1
  }
}

#macro Shiny(K, S)
  texture {
    pigment { color rgb K }
    finish { ambient 0.1 * (1 - S) diffuse (1 - S) specular 0 phong 0 reflection { S metallic } }
  }
#end

plane {
  y, -1
  texture {
    pigment { checker color rgb 0.1 color rgb 0.9 }
    finish { ambient 0.1 * 0.7 diffuse 0.7 specular 0 phong 0 reflection { 0.3 metallic } }
  }
}

sphere { <-2.2, 0, 2.5>, 1 Shiny(<0.9, 0.2, 0.2>, 0.8) }
sphere { < 0.0, 0, 2.5>, 1 Shiny(<0.2, 0.9, 0.2>, 0.8) }
sphere { < 2.2, 0, 2.5>, 1 Shiny(<0.2, 0.2, 0.9>, 0.8) }
sphere { <-2.2, 0, 4.7>, 1 Shiny(<0.9, 0.9, 0.2>, 0.8) }
sphere { < 0.0, 0, 4.7>, 1 Shiny(<0.9, 0.2, 0.9>, 0.8) }
sphere { < 2.2, 0, 4.7>, 1 Shiny(<0.2, 0.9, 0.9>, 0.8) }
sphere { <-2.2, 0, 6.9>, 1 Shiny(<0.9, 0.5, 0.1>, 0.8) }
sphere { < 0.0, 0, 6.9>, 1 Shiny(<0.5, 0.1, 0.9>, 0.8) }
sphere { < 2.2, 0, 6.9>, 1 Shiny(<0.1, 0.9, 0.5>, 0.8) }
