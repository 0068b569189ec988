#pragma once
// What `btflut view` opens: a bank, a dataset (baked, or found baked: bake_cache.h) or a scene file, as a
// scene; a single material becomes one quad.
//
//   Result<ViewerInput> in = openInput(options);   // in->scene, in->title

#include <nlohmann/json.hpp>
#include <string>

#include "core/data/scene.h"
#include "core/result.h"
#include "viewer/viewer.h"

namespace btflut {

// What the viewer shows: a scene, built around one quad unless the input was a scene file.
struct ViewerInput {
    Scene scene;
    bool singleQuad = false;
    std::string title;
    nlohmann::json modelParameters;  ///< a synthetic dataset's parameters, when known
    std::string temporaryBank;       ///< baked from a dataset for this session; removed at exit
    std::string bakedBank;           ///< baked from the dataset opened (or found baked in the cache)
    bool bakeReused = false;         ///< the bank came from the cache (bake_cache.h)
};

/// Opens `options.input` (the bundled default material when empty). Errors name the file: missing,
/// not a bank, dataset or scene, or what reading it found wrong.
Result<ViewerInput> openInput(const ViewerOptions& options);

/// Removes a session's temporary bank whatever way the viewer ends.
struct TemporaryFile {
    std::string path;
    TemporaryFile() = default;
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;
    ~TemporaryFile();
};

}  // namespace btflut
