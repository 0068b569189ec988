#include "core/data/dataset.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include <regex>
#include <sstream>
#include "core/io/json_text.h"

#include "core/io/file_io.h"
#include "core/parallel.h"

namespace btflut {

namespace fs = std::filesystem;

bool isImageExtension(const std::string& ext) {
    return ext == "png" || ext == "jpg" || ext == "jpeg" || ext == "tga" || ext == "bmp";
}

namespace {

const char* const kManifestName = "btflut-dataset.json";

std::string stem(const std::string& path) { return fs::path(path).stem().string(); }

// The file name of a path as written, '/' or '\\' between its folders (RTIBuilder's .lp files
// hold Windows paths).
std::string fileNameAsWritten(const std::string& path) {
    const std::size_t cut = path.find_last_of("/\\");
    return cut == std::string::npos ? path : path.substr(cut + 1);
}

// A light vector of an RTI or photometric-stereo file: within kRoundedLightTolerance of unit
// length, normalised (counted in `normalised`).
Result<Direction> roundedLight(Vec3 v, const std::string& where, std::size_t& normalised) {
    Result<Direction> d = directionFromMeasuredVector(v, where, kRoundedLightTolerance);
    if (d && std::abs(std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z) - 1) > 1e-3) ++normalised;
    return d;
}

std::string normalisedNote(const std::string& file, std::size_t count) {
    return file + ": " + std::to_string(count) + " light vector(s) up to " +
           std::to_string(static_cast<int>(kRoundedLightTolerance * 100)) +
           "% from unit length (rounded by another tool), normalised";
}

std::string joinPath(const std::string& folder, const std::string& relative) {
    return (fs::path(folder) / relative).lexically_normal().string();
}

// Splits text into lines, dropping '\r' and trailing blanks; keeps 1-based numbering.
std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
        lines.push_back(line);
    }
    return lines;
}

// The entries of a folder (unreadable folders are an error, not an exception).
Result<std::vector<fs::path>> listFolder(const std::string& folder) {
    std::error_code ec;
    std::vector<fs::path> entries;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) entries.push_back(it->path());
    if (ec) return Error{folder + ": cannot list the folder (" + ec.message() + ")"};
    return entries;
}

bool isBlank(const std::string& line) {
    return std::all_of(line.begin(), line.end(), [](unsigned char c) { return std::isspace(c) != 0; });
}

// Reads "N" from the first non-blank line; returns the index of the line after it.
Result<std::size_t> readCountLine(const std::vector<std::string>& lines, const std::string& file, std::size_t& next) {
    next = 0;
    while (next < lines.size() && isBlank(lines[next])) ++next;
    if (next == lines.size()) return Error{file + ": empty file, expected an image count"};
    std::istringstream in(lines[next]);
    long long count = -1;
    std::string rest;
    if (!(in >> count) || (in >> rest) || count <= 0)
        return Error{file + ":" + std::to_string(next + 1) + ": expected a positive image count, got '" + lines[next] +
                     "'"};
    ++next;
    return static_cast<std::size_t>(count);
}

Result<Vec3> parseVector(const std::string& text, const std::string& where) {
    std::istringstream in(text);
    std::string tok[3], extra;
    if (!(in >> tok[0] >> tok[1] >> tok[2]) || (in >> extra))
        return Error{where + ": expected 'x y z', got '" + text + "'"};
    double v[3];
    for (int i = 0; i < 3; ++i) {
        try {
            std::size_t used = 0;
            v[i] = std::stod(tok[i], &used);
            if (used != tok[i].size()) throw std::invalid_argument(tok[i]);
        } catch (const std::exception&) {
            // stod throws out_of_range for subnormals; treat any failure as malformed.
            if (tok[i] == "nan" || tok[i] == "NaN" || tok[i] == "-nan")
                v[i] = std::numeric_limits<double>::quiet_NaN();
            else
                return Error{where + ": '" + tok[i] + "' is not a number"};
        }
    }
    return Vec3{v[0], v[1], v[2]};
}

Result<Dataset> openPsmFolder(const std::string& folder) {
    std::string lightsFile = joinPath(folder, "lights.txt");
    Result<Bytes> text = readFile(lightsFile);
    if (!text) return Error{text.error()};
    std::size_t normalised = 0;
    Result<std::vector<Direction>> lights =
        parseLightsTxt(std::string(text->begin(), text->end()), lightsFile, &normalised);
    if (!lights) return Error{lights.error()};

    // Images are NAME.K.ext; the mask NAME.mask.ext. Exactly one NAME must be present.
    static const std::regex imageName(R"(^(.+)\.(\d+)\.([A-Za-z]+)$)");
    static const std::regex maskName(R"(^(.+)\.mask\.([A-Za-z]+)$)");
    std::map<std::string, std::map<long, std::string>> byName;
    std::map<std::string, std::string> masks;
    Result<std::vector<fs::path>> entries = listFolder(folder);
    if (!entries) return Error{entries.error()};
    for (const fs::path& entry : *entries) {
        std::string file = entry.filename().string();
        if (!isImageExtension(fileExtension(file))) continue;
        std::smatch m;
        if (std::regex_match(file, m, imageName)) {
            const std::string digits = m[2];
            long k = 0;
            if (std::from_chars(digits.data(), digits.data() + digits.size(), k).ec != std::errc{})
                return Error{entry.string() + ": image number " + digits + " is out of range"};
            byName[m[1]][k] = entry.string();
        } else if (std::regex_match(file, m, maskName)) {
            masks[m[1]] = entry.string();
        }
    }
    if (byName.empty()) return Error{folder + ": photometric-stereo folder has lights.txt but no NAME.K images"};
    if (byName.size() > 1)
        return Error{folder + ": several image sets (" + byName.begin()->first + ", " +
                     std::next(byName.begin())->first + "); expected one NAME.K series"};
    const auto& [name, files] = *byName.begin();
    Dataset ds;
    ds.source = folder;
    ds.format = "psm";
    if (auto m = masks.find(name); m != masks.end()) ds.maskPath = m->second;
    for (std::size_t k = 0; k < lights->size(); ++k) {
        auto f = files.find(static_cast<long>(k));
        if (f == files.end())
            return Error{folder + ": lights.txt lists " + std::to_string(lights->size()) + " lights but image " + name +
                         "." + std::to_string(k) + ".* is missing"};
        ds.images.push_back({stem(f->second), f->second, (*lights)[k], Direction{}});
    }
    if (files.size() != lights->size())
        return Error{folder + ": " + std::to_string(files.size()) + " images " + name + ".K but lights.txt lists " +
                     std::to_string(lights->size()) + " lights"};
    if (normalised > 0) ds.notes.push_back(normalisedNote(lightsFile, normalised));
    return ds;
}

Result<Dataset> openBonnFolder(const std::string& folder) {
    Dataset ds;
    ds.source = folder;
    ds.format = "bonn";
    ds.rectified = true;  // UBO2003's images are rectified to the sample's frame
    Result<std::vector<fs::path>> entries = listFolder(folder);
    if (!entries) return Error{entries.error()};
    std::vector<std::string> names;
    for (const fs::path& entry : *entries) {
        std::error_code ec;
        if (fs::is_regular_file(entry, ec)) names.push_back(entry.filename().string());
    }
    std::sort(names.begin(), names.end());
    for (const std::string& name : names) {
        if (!isImageExtension(fileExtension(name))) continue;
        Result<DatasetImage> image = parseBonnName(name, folder);
        if (image) ds.images.push_back(*image);
    }
    if (ds.images.empty())
        return Error{folder + ": not a dataset (no " + kManifestName +
                     ", lights.txt, .lp file or Bonn 'tl015 pl000 tv000 pv000' images)"};
    return ds;
}

Result<Dataset> openFile(const std::string& path, const std::string& ext) {
    Result<Bytes> bytes = readFile(path);
    if (!bytes) return Error{bytes.error()};
    std::string text(bytes->begin(), bytes->end());
    std::string folder = fs::path(path).parent_path().string();
    if (folder.empty()) folder = ".";
    if (ext == "json") return parseManifest(text, path, folder);
    Result<Dataset> rti = parseLpFile(text, path, folder);
    if (!rti) return rti;
    // RTIBuilder writes absolute paths, often from another machine: an image not found as
    // written is looked for by its file name beside the .lp file.
    std::error_code ec;
    std::size_t moved = 0;
    for (DatasetImage& image : rti->images) {
        if (fs::exists(image.path, ec)) continue;
        const std::string beside = joinPath(folder, fileNameAsWritten(image.path));
        if (!fs::exists(beside, ec))
            return Error{path + ":" + std::to_string(image.line) + ": image " + image.path + " not found, nor " +
                         fileNameAsWritten(image.path) + " beside the .lp file"};
        image.path = beside;
        ++moved;
    }
    if (moved > 0)
        rti->notes.push_back(path + ": " + std::to_string(moved) +
                             " image path(s) not found as written; their file names "
                             "beside the .lp file used instead");
    // RTI captures have no place for a mask in the .lp file: a mask.png beside it is the mask.
    if (fs::is_regular_file(fs::path(folder) / "mask.png", ec)) rti->maskPath = joinPath(folder, "mask.png");
    return rti;
}

}  // namespace

bool Dataset::fixedView() const {
    return std::all_of(images.begin(), images.end(),
                       [&](const DatasetImage& im) { return angleBetween(im.view, images.front().view) < 1e-9; });
}

std::pair<Direction, std::size_t> Dataset::fewestLightsPerView() const {
    constexpr double kSame = 1e-6;  // as the bank's kSameDirection
    // Each distinct view with its distinct lights, in one pass: images x (views + lights)
    // comparisons, not images squared (a BTF has thousands of images and ~81 views).
    std::vector<std::pair<Direction, std::vector<Direction>>> views;
    for (const DatasetImage& im : images) {
        auto view = std::find_if(views.begin(), views.end(),
                                 [&](const auto& v) { return angleBetween(v.first, im.view) < kSame; });
        if (view == views.end()) view = views.insert(views.end(), {im.view, {}});
        std::vector<Direction>& lights = view->second;
        if (std::none_of(lights.begin(), lights.end(), [&](Direction l) { return angleBetween(l, im.light) < kSame; }))
            lights.push_back(im.light);
    }
    std::pair<Direction, std::size_t> fewest{{}, images.size()};
    for (const auto& [view, lights] : views)
        if (lights.size() < fewest.second) fewest = {view, lights.size()};
    return fewest;
}

Result<std::vector<Direction>> parseLightsTxt(const std::string& text, const std::string& file,
                                              std::size_t* normalised) {
    std::size_t rounded = 0;
    std::vector<std::string> lines = splitLines(text);
    std::size_t next = 0;
    Result<std::size_t> count = readCountLine(lines, file, next);
    if (!count) return Error{count.error()};
    std::vector<Direction> lights;
    for (; next < lines.size(); ++next) {
        if (isBlank(lines[next])) continue;
        std::string where = file + ":" + std::to_string(next + 1);
        if (lights.size() == *count)
            return Error{where + ": more light lines than the declared count " + std::to_string(*count)};
        Result<Vec3> v = parseVector(lines[next], where);
        if (!v) return Error{v.error()};
        Result<Direction> d = roundedLight(*v, where, rounded);
        if (!d) return Error{d.error()};
        lights.push_back(*d);
    }
    if (normalised) *normalised = rounded;
    if (lights.size() != *count)
        return Error{file + ": declares " + std::to_string(*count) + " lights but lists " +
                     std::to_string(lights.size())};
    return lights;
}

Result<Dataset> parseLpFile(const std::string& text, const std::string& file, const std::string& folder) {
    std::vector<std::string> lines = splitLines(text);
    std::size_t next = 0;
    Result<std::size_t> count = readCountLine(lines, file, next);
    if (!count) return Error{count.error()};
    Dataset ds;
    ds.source = file;
    ds.format = "rti";
    std::size_t rounded = 0;
    for (; next < lines.size(); ++next) {
        if (isBlank(lines[next])) continue;
        std::string where = file + ":" + std::to_string(next + 1);
        if (ds.images.size() == *count)
            return Error{where + ": more image lines than the declared count " + std::to_string(*count)};
        // "relative/path x y z": the path may hold spaces, so the vector is the last three
        // fields.
        std::string line = lines[next];
        std::size_t cut = line.size();
        for (int field = 0; field < 3; ++field) {
            while (cut > 0 && std::isspace(static_cast<unsigned char>(line[cut - 1]))) --cut;
            while (cut > 0 && !std::isspace(static_cast<unsigned char>(line[cut - 1]))) --cut;
        }
        std::string path = line.substr(0, cut);
        while (!path.empty() && std::isspace(static_cast<unsigned char>(path.back()))) path.pop_back();
        while (!path.empty() && std::isspace(static_cast<unsigned char>(path.front()))) path.erase(0, 1);
        if (path.empty()) return Error{where + ": expected 'path x y z', got '" + line + "'"};
        Result<Vec3> v = parseVector(line.substr(cut), where);
        if (!v) return Error{v.error()};
        Result<Direction> light = roundedLight(*v, where, rounded);
        if (!light) return Error{light.error()};
        ds.images.push_back(
            {stem(fileNameAsWritten(path)), joinPath(folder, path), *light, Direction{}, static_cast<int>(next + 1)});
    }
    if (ds.images.size() != *count)
        return Error{file + ": declares " + std::to_string(*count) + " images but lists " +
                     std::to_string(ds.images.size())};
    if (rounded > 0) ds.notes.push_back(normalisedNote(file, rounded));
    return ds;
}

Result<Dataset> parseManifest(const std::string& text, const std::string& file, const std::string& folder) {
    using nlohmann::json;
    Result<json> parsed = parseJsonText(text, file);
    if (!parsed) return Error{parsed.error()};
    json doc = std::move(*parsed);
    if (!doc.is_object() || !doc.contains("images") || !doc["images"].is_array())
        return Error{file + ": not a btflut dataset manifest (no \"images\" array)"};
    if (doc.contains("btflut_dataset") && doc["btflut_dataset"] != 1)
        return Error{file + ": unsupported manifest version " + jsonText(doc["btflut_dataset"], -1)};
    Dataset ds;
    ds.source = file;
    ds.format = "manifest";
    if (doc.contains("rectified")) {
        if (!doc["rectified"].is_boolean()) return Error{file + ": \"rectified\" must be true or false"};
        ds.rectified = doc["rectified"].get<bool>();
    }
    if (doc.contains("mask")) {
        if (!doc["mask"].is_string()) return Error{file + ": \"mask\" must be a file name"};
        ds.maskPath = joinPath(folder, doc["mask"].get<std::string>());
    }
    auto readAngles = [&](const json& entry, const char* key, std::size_t index, Result<Direction>& out) {
        std::string where = file + ": images[" + std::to_string(index) + "]." + key;
        if (!entry.contains(key)) {
            out = Direction{};  // frontal
            return;
        }
        const json& d = entry[key];
        if (!d.is_object() || !d.contains("theta") || !d.contains("phi") || !d["theta"].is_number() ||
            !d["phi"].is_number()) {
            out = Error{where + ": expected {\"theta\": degrees, \"phi\": degrees}"};
            return;
        }
        out = directionFromDegrees(d["theta"].get<double>(), d["phi"].get<double>(), where);
    };
    for (std::size_t i = 0; i < doc["images"].size(); ++i) {
        const json& entry = doc["images"][i];
        std::string where = file + ": images[" + std::to_string(i) + "]";
        if (!entry.is_object() || !entry.contains("file") || !entry["file"].is_string())
            return Error{where + ": expected an object with a \"file\" name"};
        if (!entry.contains("light")) return Error{where + ": no \"light\" direction"};
        Result<Direction> light = Direction{}, view = Direction{};
        readAngles(entry, "light", i, light);
        if (!light) return Error{light.error()};
        readAngles(entry, "view", i, view);
        if (!view) return Error{view.error()};
        std::string path = joinPath(folder, entry["file"].get<std::string>());
        std::string name =
            entry.contains("name") && entry["name"].is_string() ? entry["name"].get<std::string>() : stem(path);
        ds.images.push_back({name, path, *light, *view});
    }
    if (ds.images.empty()) return Error{file + ": manifest lists no images"};
    return ds;
}

Result<DatasetImage> parseBonnName(const std::string& fileName, const std::string& folder) {
    static const std::regex pattern(R"(^tl(\d{1,3})[ _]pl(\d{1,3})[ _]tv(\d{1,3})[ _]pv(\d{1,3})\.\w+$)",
                                    std::regex::icase);
    std::smatch m;
    if (!std::regex_match(fileName, m, pattern))
        return Error{fileName + ": not a Bonn BTF image name (tlTTT plPPP tvTTT pvPPP)"};
    std::string where = joinPath(folder, fileName);
    Result<Direction> light = directionFromDegrees(std::stod(m[1]), std::stod(m[2]), where);
    if (!light) return Error{light.error()};
    Result<Direction> view = directionFromDegrees(std::stod(m[3]), std::stod(m[4]), where);
    if (!view) return Error{view.error()};
    return DatasetImage{stem(fileName), where, *light, *view};
}

Result<Mask> loadDatasetMask(const Dataset& dataset, int width, int height) {
    if (dataset.maskPath.empty()) return fullMask(width, height);
    return loadMask(dataset.maskPath, width, height);
}

Status requireSameSize(const Image& image, const std::string& path, int width, int height,
                       const std::string& firstPath) {
    if (image.width == width && image.height == height) return success();
    return Error{path + ": image is " + std::to_string(image.width) + "x" + std::to_string(image.height) + " but " +
                 firstPath + " is " + std::to_string(width) + "x" + std::to_string(height)};
}

Result<Dataset> openDataset(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return Error{path + ": no such file or folder"};
    if (!fs::is_directory(path, ec)) {
        std::string ext = fileExtension(path);
        if (ext == "json" || ext == "lp") return openFile(path, ext);
        return Error{path + ": not a dataset (expected a folder, a .json manifest or an .lp file)"};
    }
    if (fs::exists(fs::path(path) / kManifestName, ec))
        return openFile((fs::path(path) / kManifestName).string(), "json");
    if (fs::exists(fs::path(path) / "lights.txt", ec)) return openPsmFolder(path);
    Result<std::vector<fs::path>> entries = listFolder(path);
    if (!entries) return Error{entries.error()};
    std::vector<std::string> lpFiles;
    for (const fs::path& entry : *entries)
        if (fileExtension(entry.string()) == "lp") lpFiles.push_back(entry.string());
    if (lpFiles.size() == 1) return openFile(lpFiles.front(), "lp");
    if (lpFiles.size() > 1) return Error{path + ": several .lp files; name the one to use"};
    return openBonnFolder(path);
}

Result<std::vector<HistogramRow>> histogramsOf(const Dataset& dataset, int bins, bool rgb) {
    const std::size_t perImage = rgb ? 3 : 1;

    // The first image fixes the size and the mask; the rest are decoded in parallel.
    const DatasetImage& first = dataset.images.front();
    Result<Image> firstImage = loadImage(first.path);
    if (!firstImage) return Error{firstImage.error()};
    Result<Mask> mask = loadDatasetMask(dataset, firstImage->width, firstImage->height);
    if (!mask) return Error{mask.error()};

    std::vector<HistogramRow> rows(dataset.images.size() * perImage);
    std::vector<std::string> errors(dataset.images.size());
    parallelFor(dataset.images.size(), 0, [&](std::size_t i) {
        const DatasetImage& info = dataset.images[i];
        Result<Image> image = i == 0 ? Result<Image>(*firstImage) : loadImage(info.path);
        if (!image) {
            errors[i] = image.error();
            return;
        }
        Status size = requireSameSize(*image, info.path, firstImage->width, firstImage->height, first.path);
        if (!size) {
            errors[i] = size.error();
            return;
        }
        if (rgb && image->channels != 3) {
            errors[i] = info.path + ": --channels rgb needs colour images, this one is grey";
            return;
        }
        std::vector<HistogramRow> own = imageHistograms(*image, *mask, info.name, info.light, info.view, bins, rgb);
        std::move(own.begin(), own.end(), rows.begin() + static_cast<std::ptrdiff_t>(i * perImage));
    });
    for (const std::string& e : errors)
        if (!e.empty()) return Error{e};
    return rows;
}

}  // namespace btflut
