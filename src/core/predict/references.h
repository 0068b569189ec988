#pragma once
// What banks that blend several references and match regions (LutBank::Prediction) are baked
// from: which measured images become the references, the regions of the sample, and the
// albedo whose chroma an lrgb bank keeps.
//
//   std::vector<std::size_t> refs = pickReferences(lights, first, 6);   // spread over the lights
//   Result<Regions> r = segmentRegions(responses, mask, 4, "rock");     // k-means on responses
//
// Picking: the first reference is the classic one (nearest frontal light); each next one is
// the light farthest on the equal-area disk from those picked (farthest-point sampling), so
// the references span the measured lights and their hull, and a light is blended from
// references lit nearly like it. (Measured against a greedy pick that best spans the images:
// bench/RESULTS.md.)
//
// Regions: each texel's grey values under a few lights spread over the measured ones, scaled
// to unit length, so that texels cluster by how they respond to the light (orientation,
// shadowing, gloss) rather than by brightness; k-means (k-means++ start, fixed seed) on the
// mask's texels, then every texel goes to its nearest centre.

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/image/image.h"
#include "core/result.h"

namespace btflut {

/// `count` indices into `lights` (distinct directions), `first` first, then farthest-point.
std::vector<std::size_t> pickReferences(const std::vector<Direction>& lights, std::size_t first, std::size_t count);

/// At most `count` of `lights` spread over them (farthest-point from the most frontal).
std::vector<std::size_t> spreadLights(const std::vector<Direction>& lights, std::size_t count);

struct Regions {
    int count = 1;
    std::vector<std::uint8_t> labels;  ///< per texel, 0 .. count - 1
};

/// Per texel response vectors: `lights` grey values in [0, 1] per texel, texel-major.
struct Responses {
    int width = 0, height = 0, lights = 0;
    std::vector<std::uint8_t> values;  ///< texels x lights, grey * 255
};

/// k-means regions from responses; refuses (naming `what`) a region left with fewer than
/// max(64, 1% of the mask) sample texels.
Result<Regions> segmentRegions(const Responses& responses, const Mask& mask, int count, const std::string& what);

/// Regions from a label image: each distinct grey value is a region, in increasing order.
/// It must be width x height; refuses more than 255 regions and regions without sample texels.
Result<Regions> regionsFromLabels(const Image& labels, const Mask& mask, int width, int height,
                                  const std::string& path);

/// Sums RGB per texel over images (any thread), for an albedo: the mean colour scaled so its
/// largest channel is 1 (only its chroma is used).
class AlbedoAccumulator {
public:
    AlbedoAccumulator(int width, int height);
    void add(const Image& image);
    Image finish() const;  ///< RGB, 8-bit

private:
    int m_width, m_height;
    std::vector<float> m_sum;
    std::mutex m_mutex;
};

}  // namespace btflut
