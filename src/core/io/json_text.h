#pragma once
// JSON files' text in and out, for every JSON file btflut reads or writes (manifests,
// scenes, model parameters, sidecars, histograms):
//   - parsing refuses, with the one-line error the command line prints ("FILE: not valid
//     JSON (...)"), anything nlohmann::json throws on (syntax, numbers out of range such as
//     1e999) and values nested deeper than kMaxJsonDepth (a 200000-deep array would
//     otherwise exhaust the stack in recursive code that walks it);
//   - writing replaces bytes that are not UTF-8 (file names are bytes on Linux) with
//     U+FFFD instead of throwing.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/result.h"

namespace btflut {

/// No btflut file needs more than a few levels.
constexpr int kMaxJsonDepth = 64;

/// A direction as the JSON files write it: {"theta": degrees, "phi": degrees}.
inline nlohmann::json directionJson(Direction d) { return {{"theta", d.thetaDegrees()}, {"phi", d.phiDegrees()}}; }

/// The JSON value of `text`, or the one-line error naming `file` (see above). Out of line:
/// nlohmann's parser and writer are compiled once, not in each of the files that read JSON.
Result<nlohmann::json> parseJsonText(const std::string& text, const std::string& file);

/// Refuses a key of `object` that is not in `known`, naming it and the nearest known key
/// ("FILE: quads[0]: unknown key 'uv_scael' (did you mean 'uv_scale'?)"): a misspelt key
/// would otherwise be ignored silently. `where` is the object's place ("FILE: quads[0]").
Status requireKnownKeys(const nlohmann::json& object, const std::vector<std::string>& known, const std::string& where);

/// The text of a JSON value (indent < 0: one line), never throwing on invalid UTF-8.
std::string jsonText(const nlohmann::json& value, int indent = 1);

}  // namespace btflut
