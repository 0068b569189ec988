#pragma once
// The texels of a repeating texture that a view reads: a span along each axis on the circle of
// the texture's size, so that a region across the texture's edge (GL_REPEAT, or bilinear
// filtering at texel 0 reading the last one) is one region. What a relit texture holds and
// what a frame needs (the scene renderer relights only the region its quads show).
//
//   TexelRegion need = TexelRegion::span(x0, x1, y0, y1, width, height);  // x0 may be < 0
//   if (!held.covers(need)) relight(held = held.merged(need));
//   for (auto [x, y, w, h] : need.rectsAt(levelWidth, levelHeight)) glScissor(x, y, w, h), draw();

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace btflut {

/// [begin, end) on a circle of `size` texels: begin in [0, size), end - begin in [0, size].
struct TexelSpan {
    int begin = 0, end = 0;

    static TexelSpan of(long long first, long long last, int size) {  // [first, last), any integers
        if (last - first >= size) return {0, size};
        if (last <= first) return {};
        const long long b = ((first % size) + size) % size;
        return {static_cast<int>(b), static_cast<int>(b + (last - first))};
    }
    bool full(int size) const { return end - begin >= size; }
    int length() const { return end - begin; }
    bool covers(TexelSpan s, int size) const {
        if (full(size) || s.length() == 0) return true;
        for (int shift : {-size, 0, size})
            if (s.begin + shift >= begin && s.end + shift <= end) return true;
        return false;
    }
    /// The shorter arc that holds both.
    TexelSpan merged(TexelSpan s, int size) const {
        if (length() == 0) return s;
        if (s.length() == 0) return *this;
        int best = size + 1;
        TexelSpan out{0, size};
        for (int shift : {-size, 0, size}) {
            const long long first = std::min(begin, s.begin + shift), last = std::max(end, s.end + shift);
            if (last - first < best) {
                best = static_cast<int>(last - first);
                out = of(first, last, size);
            }
        }
        return out;
    }
    /// At a texture `levelSize` texels long (a mip level): the texels holding this span's, in at
    /// most two pieces [first, last) within [0, levelSize).
    std::vector<std::array<int, 2>> piecesAt(int size, int levelSize) const {
        if (full(size)) return {{0, levelSize}};
        const auto scaled = [&](long long v, bool up) {
            const long long n = v * levelSize;
            return static_cast<int>(up ? (n + size - 1) / size : n / size);
        };
        const int first = scaled(begin, false), last = scaled(end, true);
        if (last - first >= levelSize) return {{0, levelSize}};
        if (last <= levelSize) return {{first, last}};
        return {{first, levelSize}, {0, last - levelSize}};
    }
};

struct TexelRegion {
    int width = 0, height = 0;  ///< the texture's size at level 0
    TexelSpan x, y;             ///< in level-0 texels

    static TexelRegion whole(int width, int height) { return {width, height, {0, width}, {0, height}}; }
    static TexelRegion span(long long x0, long long x1, long long y0, long long y1, int width, int height) {
        return {width, height, TexelSpan::of(x0, x1, width), TexelSpan::of(y0, y1, height)};
    }
    bool empty() const { return x.length() == 0 || y.length() == 0; }
    bool isWhole() const { return x.full(width) && y.full(height); }
    std::uint64_t texels() const {
        return static_cast<std::uint64_t>(x.length()) * static_cast<std::uint64_t>(y.length());
    }
    bool covers(const TexelRegion& r) const { return r.empty() || (x.covers(r.x, width) && y.covers(r.y, height)); }
    TexelRegion merged(const TexelRegion& r) const {
        if (empty()) return r;
        if (r.empty()) return *this;
        return {width, height, x.merged(r.x, width), y.merged(r.y, height)};
    }
    /// The rectangles {x, y, w, h} (at most four) of a level `levelWidth` x `levelHeight` that
    /// hold the region's texels.
    std::vector<std::array<int, 4>> rectsAt(int levelWidth, int levelHeight) const {
        std::vector<std::array<int, 4>> out;
        if (empty()) return out;
        for (const auto& [x0, x1] : x.piecesAt(width, levelWidth))
            for (const auto& [y0, y1] : y.piecesAt(height, levelHeight)) out.push_back({x0, y0, x1 - x0, y1 - y0});
        return out;
    }
    /// Texels of those rectangles.
    std::uint64_t texelsAt(int levelWidth, int levelHeight) const {
        std::uint64_t n = 0;
        for (const auto& r : rectsAt(levelWidth, levelHeight))
            n += static_cast<std::uint64_t>(r[2]) * static_cast<std::uint64_t>(r[3]);
        return n;
    }
};

}  // namespace btflut
