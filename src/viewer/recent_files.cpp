#include "viewer/recent_files.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "core/io/file_io.h"

namespace btflut {

namespace {

constexpr std::size_t kMostRecent = 10;

std::filesystem::path listPath() {
    if (const char* config = std::getenv("XDG_CONFIG_HOME"); config && *config)
        return std::filesystem::path(config) / "btflut" / "recent.txt";
    const char* home = std::getenv("HOME");
    return std::filesystem::path(home && *home ? home : ".") / ".config" / "btflut" / "recent.txt";
}

}  // namespace

std::vector<std::string> loadRecentFiles() {
    Result<Bytes> bytes = readFile(listPath().string());
    std::vector<std::string> paths;
    if (!bytes) return paths;
    std::istringstream in(std::string(bytes->begin(), bytes->end()));
    for (std::string line; std::getline(in, line) && paths.size() < kMostRecent;)
        if (!line.empty()) paths.push_back(line);
    return paths;
}

bool rememberRecentFile(const std::string& path) {
    std::error_code ec;
    const std::string absolute = std::filesystem::absolute(path, ec).lexically_normal().string();
    std::vector<std::string> paths = loadRecentFiles();
    paths.erase(std::remove(paths.begin(), paths.end(), absolute), paths.end());
    paths.insert(paths.begin(), absolute);
    if (paths.size() > kMostRecent) paths.resize(kMostRecent);
    std::string text;
    for (const std::string& p : paths) text += p + "\n";
    const std::filesystem::path file = listPath();
    std::filesystem::create_directories(file.parent_path(), ec);
    return static_cast<bool>(writeFileAtomically(file.string(), text));
}

}  // namespace btflut
