#pragma once
// Draws a Scene (core/scene.h) into an image with OpenGL, doing only the work the view needs:
// quads outside the frustum are culled, and only materials that a visible quad uses are
// loaded and uploaded. Needs a current context (context.h).
//
//   RenderStats stats;
//   Result<Image> img = renderScene(scene, stats);

#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"

namespace btflut {

struct RenderStats {
    std::vector<std::string> loadedMaterials;   ///< names, in load order
    std::vector<std::string> skippedMaterials;  ///< used by no visible quad: never read
    std::size_t quadsDrawn = 0, quadsCulled = 0, quadsUnlit = 0;
    std::size_t textureBytes = 0;  ///< reference textures with mipmaps, plus LUT textures
};

Result<Image> renderScene(const Scene& scene, RenderStats& stats);

}  // namespace btflut
