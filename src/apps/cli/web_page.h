#pragma once
// The page `btflut export --web` writes: one HTML file that opens from disk with no network,
// the engine export's files inside it as data: URLs, relit by WebGL2 through the include's
// GLSL ES form. The page and its scripts are src/web/, compiled in.

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace btflut::cli {

/// src/web/NAME, compiled in (empty if there is none).
std::string_view embeddedWebFile(std::string_view name);

/// The page for an engine export: its sidecar and its files (name, bytes), as `export -o DIR/`
/// writes them; `name` titles it.
std::string webPage(const std::string& name, const nlohmann::json& material,
                    const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace btflut::cli
