#include "core/io/json_text.h"

#include <algorithm>
#include <set>

#include "core/io/closest_name.h"

namespace btflut {

Result<nlohmann::json> parseJsonText(const std::string& text, const std::string& file) {
    struct TooDeep {};
    struct Twice {
        std::string key;
    };
    using Event = nlohmann::json::parse_event_t;
    // The keys of each object being read, innermost last: a key given twice would keep its
    // last value without a word (a scene's "light" twice), so it is refused.
    std::vector<std::set<std::string>> open;
    try {
        return nlohmann::json::parse(text, [&](int depth, Event event, nlohmann::json& value) {
            if (depth > kMaxJsonDepth) throw TooDeep{};
            if (event == Event::object_start) open.emplace_back();
            if (event == Event::object_end && !open.empty()) open.pop_back();
            if (event == Event::key && !open.empty() && !open.back().insert(value.get<std::string>()).second)
                throw Twice{value.get<std::string>()};
            return true;
        });
    } catch (const TooDeep&) {
        return Error{file + ": not valid JSON (nested deeper than " + std::to_string(kMaxJsonDepth) + " levels)"};
    } catch (const Twice& twice) {
        return Error{file + ": the key \"" + twice.key +
                     "\" is given twice in one object (JSON would keep the last silently); give it once"};
    } catch (const nlohmann::json::exception& e) {
        return Error{file + ": not valid JSON (" + e.what() + ")"};
    }
}

Status requireKnownKeys(const nlohmann::json& object, const std::vector<std::string>& known, const std::string& where) {
    if (!object.is_object()) return success();
    for (const auto& item : object.items()) {
        if (std::find(known.begin(), known.end(), item.key()) != known.end()) continue;
        const std::string guess = closestName(item.key(), known);
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        return Error{where + ": unknown key '" + item.key() + "' (" +
                     (guess.empty() ? "known: " + list : "did you mean '" + guess + "'?") + ")"};
    }
    return success();
}

std::string jsonText(const nlohmann::json& value, int indent) {
    return value.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace) + (indent >= 0 ? "\n" : "");
}

}  // namespace btflut
