#pragma once
// The numbers btflut's C++ and its shaders share, written once as #defines both languages
// read: C++ includes this header; src/gl/CMakeLists.txt copies its #define lines into the
// include (shaders/btflut.glsl, at "btflut: constants"), which every btflut program, every
// exported form (GLSL ES, HLSL, Godot) and the web page's reader (btflut_material.js,
// `constants`) start from. Change one here and all of them follow.

// Predictions are integer arithmetic in 1 / BTFLUT_WEIGHT_UNIT (light_model.h, kWeightUnit).
#define BTFLUT_WEIGHT_UNIT 4096
// The most planes a light model has (LightModel::kMaxPlanes; the shader's arrays).
#define BTFLUT_MAX_PLANES 32
// A bank's predictor kind in material.json and btflut.glsl's BtflutPredictor.kind.
#define BTFLUT_KIND_MODEL 1
#define BTFLUT_KIND_REFERENCES 2
#define BTFLUT_KIND_LEARNED 3
// A light model's basis (LightBasis; BtflutPredictor.basis).
#define BTFLUT_BASIS_PTM 0
#define BTFLUT_BASIS_HSH 1
#define BTFLUT_BASIS_RBF 2
#define BTFLUT_BASIS_BLN 3
// A learned model's decoder on the GPU (learned_model.h, LearnedModel::gpuNetwork): its widest
// layer and its most hidden layers per network, the shader's arrays.
#define BTFLUT_LEARNED_WIDTH 64
#define BTFLUT_LEARNED_HIDDEN 4
