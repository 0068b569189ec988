#pragma once
// Synthetic image sets of Gaussian rough surfaces: what `btflut synth` writes, readable by
// everything that reads datasets.
//
//   Result<SynthMaterial> m = synthPreset("concrete");
//   Status s = writeSynthDataset(*m, curetC2(), "out/concrete", {});
//
// A folder holds one PNG per geometry entry (NAME.png, grey), mask.png (the whole image is
// the sample), btflut-dataset.json (directions, and the parameters that made it) and, when
// the camera is fixed, synth.lp. The folder is written under a temporary name and renamed
// into place, so a failure leaves nothing half-written.

#include <functional>
#include <string>
#include <vector>

#include "core/physics/geometry.h"
#include "core/physics/surface.h"
#include "core/synth/height_field.h"

namespace btflut {

struct SynthMaterial {
    HeightFieldSpec surface;     ///< size, rms slopes, anisotropy, correlation length, seed
    SurfaceModel model;          ///< local BRDF and gain (roughness follows surface.roughness)
    double albedoVariation = 0;  ///< 0..1: albedo = 1 - variation * u, u a smooth random field in [0, 1]
    double ambient = 0;          ///< constant diffuse irradiance added to every surface point
    double noise = 0;            ///< sensor noise, standard deviation per pixel
};

/// concrete (Lambertian r 0.4), foil (Torrance-Sparrow r 0.4, sigma 0.13), plastic (0.7
/// Lambert + 0.3 Torrance-Sparrow, r 0.4), corduroy (Lambertian, r 0.6 along x, 0.15 across):
/// the paper's Fig. 9 materials plus an anisotropic one.
Result<SynthMaterial> synthPreset(const std::string& name);

/// Checks the ranges of everything in a material; errors name the parameter.
Status validateSynthMaterial(const SynthMaterial& material);

struct SynthOutput {
    int samplesPerAxis = 2;
    int bitDepth = 8;
    bool force = false;  ///< replace the files of an earlier synth output in the folder (others stay)
    int threads = 0;
    std::function<void(std::size_t, std::size_t)> progress;
};

Status writeSynthDataset(const SynthMaterial& material, const std::vector<Geometry>& geometry,
                         const std::string& folder, const SynthOutput& output);

}  // namespace btflut
