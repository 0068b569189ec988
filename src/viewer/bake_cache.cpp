#include "viewer/bake_cache.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <vector>

namespace btflut {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kKept = 8;  // banks of a large capture take tens of MB each

fs::path cacheFolder() {
    if (const char* cache = std::getenv("XDG_CACHE_HOME"); cache && *cache) return fs::path(cache) / "btflut" / "view";
    const char* home = std::getenv("HOME");
    return fs::path(home && *home ? home : fs::temp_directory_path().string()) / ".cache" / "btflut" / "view";
}

// FNV-1a, 64 bits: a name, not a defence against anyone (the files are the user's own).
struct Fingerprint {
    std::uint64_t value = 14695981039346656037ull;
    void add(const std::string& text) {
        for (unsigned char c : text) value = (value ^ c) * 1099511628211ull;
        add(text.size());
    }
    void add(std::uint64_t number) {
        for (int byte = 0; byte < 8; ++byte) value = (value ^ ((number >> (8 * byte)) & 0xff)) * 1099511628211ull;
    }
    // A file by its absolute path, size and time of last change (missing: only its name).
    void addFile(const std::string& path) {
        std::error_code ec;
        add(fs::absolute(path, ec).lexically_normal().string());
        const std::uintmax_t size = fs::file_size(path, ec);
        add(ec ? 0 : static_cast<std::uint64_t>(size));
        const auto changed = fs::last_write_time(path, ec);
        add(ec ? 0 : static_cast<std::uint64_t>(changed.time_since_epoch().count()));
    }
};

}  // namespace

std::string bakeCachePath(const Dataset& dataset, const std::string& settings) {
    Fingerprint key;
    key.addFile("/proc/self/exe");  // a rebuilt btflut may bake differently
    key.add(settings);
    key.addFile(dataset.source);
    std::error_code ec;
    if (fs::is_directory(dataset.source, ec)) key.addFile((fs::path(dataset.source) / "btflut-dataset.json").string());
    key.add(dataset.format);
    key.add(dataset.rectified ? 1 : 0);
    if (!dataset.maskPath.empty()) key.addFile(dataset.maskPath);
    for (const DatasetImage& image : dataset.images) {
        key.addFile(image.path);
        for (double v : {image.light.theta, image.light.phi, image.view.theta, image.view.phi})
            key.add(static_cast<std::uint64_t>(v * 1e9));
    }
    char name[32];
    std::snprintf(name, sizeof name, "%016llx.btflut", static_cast<unsigned long long>(key.value));
    return (cacheFolder() / name).string();
}

void pruneBakeCache(const std::string& kept) {
    std::error_code ec;
    fs::last_write_time(kept, fs::file_time_type::clock::now(), ec);
    std::vector<fs::directory_entry> banks;
    for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(kept).parent_path(), ec))
        if (entry.path().extension() == ".btflut") banks.push_back(entry);
    if (banks.size() <= kKept) return;
    std::sort(banks.begin(), banks.end(), [](const fs::directory_entry& a, const fs::directory_entry& b) {
        std::error_code e;
        return a.last_write_time(e) > b.last_write_time(e);
    });
    for (std::size_t i = kKept; i < banks.size(); ++i) fs::remove(banks[i].path(), ec);
}

}  // namespace btflut
