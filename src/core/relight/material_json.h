#pragma once
// The sidecar of an engine export, material.json (docs/engines.md): everything a loader needs
// to upload an EngineMaterial's files and fill btflut.glsl's structs. Written beside the
// material it describes, so the schema has one home; `btflut export` writes the files.
//
//   nlohmann::json side = materialJson(bank, *engineMaterial(bank, "m.btflut"));

#include <nlohmann/json.hpp>
#include <string>

#include "core/bank/lut_bank.h"
#include "core/relight/engine_material.h"

namespace btflut {

/// The file of plane image k of a material with a predictor: planes-K.png.
std::string planeImageName(std::size_t k);

/// material.json for `material`, made from `bank`: version 1 for banks of LUTs (loaders
/// written for it still read them), 2 with the "predictor" object for banks with one.
nlohmann::json materialJson(const LutBank& bank, const EngineMaterial& material);

}  // namespace btflut
