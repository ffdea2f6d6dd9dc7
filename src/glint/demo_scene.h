#pragma once
// The scene `glint render` draws when given none: the article's Figure 14.
namespace glint {
extern const char* const kDemoScene;      ///< YAML text of scenes/seed/fig14-reflections.yaml
extern const char* const kDemoSceneName;  ///< how diagnostics name it
}  // namespace glint
