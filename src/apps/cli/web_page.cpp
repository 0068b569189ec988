#include "cli/web_page.h"

#include <zlib.h>

#include "core/check.h"

namespace btflut::cli {

namespace {

std::string base64(std::string_view bytes) {
    static const char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const auto byte = [&](std::size_t k) { return k < bytes.size() ? static_cast<unsigned char>(bytes[k]) : 0u; };
        const unsigned triple = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
        out += kDigits[triple >> 18 & 63];
        out += kDigits[triple >> 12 & 63];
        out += i + 1 < bytes.size() ? kDigits[triple >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? kDigits[triple & 63] : '=';
    }
    return out;
}

// zlib's format, as the browser's DecompressionStream('deflate') reads it: the page's scripts
// and the include are a fifth of their size so.
std::string deflated(std::string_view text) {
    uLongf size = compressBound(static_cast<uLong>(text.size()));
    std::string out(size, '\0');
    const int status =
        compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(text.data()),
                  static_cast<uLong>(text.size()), Z_BEST_COMPRESSION);
    BTFLUT_CHECK(status == Z_OK);
    out.resize(size);
    return out;
}

// `text` with `marker` (which must be there once) replaced by `value`.
std::string replaced(std::string text, std::string_view marker, std::string_view value) {
    const std::size_t at = text.find(marker);
    BTFLUT_CHECK(at != std::string::npos && text.find(marker, at + 1) == std::string::npos);
    return text.replace(at, marker.size(), value);
}

}  // namespace

std::string webPage(const std::string& name, const nlohmann::json& material,
                    const std::vector<std::pair<std::string, std::string>>& files) {
    nlohmann::json data{{"name", name}, {"material", material}, {"files", nlohmann::json::object()}};
    std::size_t bytes = 0;
    for (const auto& [file, content] : files) {
        bytes += content.size();
        if (file == "btflut_es.glsl") data["include"] = base64(deflated(content));
        const bool png = file.size() > 4 && file.compare(file.size() - 4, 4, ".png") == 0;
        if (png || file == "weights.bin" || file == "btflut_network.glsl")  // a learned decoder's source too
            data["files"][file] =
                std::string(png ? "data:image/png;base64," : "data:application/octet-stream;base64,") + base64(content);
    }
    BTFLUT_CHECK(data.contains("include"));
    data["bytes"] = bytes;  // the engine export's files, as the page says
    // The reader, then the page's parts by job in one strict function: they share its names.
    std::string code = std::string(embeddedWebFile("btflut_material.js")) + "\n(function () {\n'use strict';\n";
    for (const char* part : {"page_state.js", "page_draw.js", "page_panel.js", "page_input.js"})
        code += std::string(embeddedWebFile(part)) + "\n";
    code += "})();\n";
    data["code"] = base64(deflated(code));  // run by the page's first script
    // JSON inside <script>: "</" written as "<\/" (the same string), so no tag ends it.
    std::string text = data.dump();
    for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3))
        text.insert(at + 1, "\\");
    std::string page(embeddedWebFile("page.html"));
    return replaced(std::move(page), "/*BTFLUT_DATA*/", text);
}

}  // namespace btflut::cli
