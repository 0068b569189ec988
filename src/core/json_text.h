#pragma once
// Internal to btflut::core: parsing a JSON file's text with the one-line error the command
// line prints ("FILE: not valid JSON (...)").

#include <nlohmann/json.hpp>
#include <string>

#include "core/result.h"

namespace btflut {

inline Result<nlohmann::json> parseJsonText(const std::string& text, const std::string& file) {
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        return Error{file + ": not valid JSON (" + e.what() + ")"};
    }
}

}  // namespace btflut
