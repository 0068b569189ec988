#include "core/image/canvas.h"

#include <algorithm>
#include <cmath>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace btflut {

Rgb paletteColour(std::size_t i) {
    static const Rgb kPalette[] = {{0.25f, 0.4f, 0.7f}, {0.85f, 0.3f, 0.1f}, {0.1f, 0.6f, 0.3f},
                                   {0.6f, 0.2f, 0.7f},  {0.9f, 0.6f, 0.0f},  {0.15f, 0.15f, 0.15f},
                                   {0.7f, 0.45f, 0.2f}, {0.85f, 0.3f, 0.55f}};
    return kPalette[i % 8];
}

Canvas::Canvas(int w, int h) : m_image(w, h, 3) { std::fill(m_image.samples.begin(), m_image.samples.end(), 1.f); }

void Canvas::fill(int x0, int y0, int x1, int y1, Rgb c) {
    x0 = std::max(x0, 0), y0 = std::max(y0, 0);
    x1 = std::min(x1, m_image.width), y1 = std::min(y1, m_image.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            m_image.at(x, y, 0) = c.r;
            m_image.at(x, y, 1) = c.g;
            m_image.at(x, y, 2) = c.b;
        }
}

void Canvas::line(double x0, double y0, double x1, double y1, Rgb c, int thickness) {
    const int steps = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))));
    for (int s = 0; s <= steps; ++s) {
        const double t = static_cast<double>(s) / steps;
        dot(x0 + (x1 - x0) * t, y0 + (y1 - y0) * t, thickness, c);
    }
}

void Canvas::dot(double x, double y, int size, Rgb c) {
    const int x0 = static_cast<int>(std::floor(x - size / 2.0 + 0.5)),
              y0 = static_cast<int>(std::floor(y - size / 2.0 + 0.5));
    fill(x0, y0, x0 + size, y0 + size, c);
}

// stb_easy_font's quads, scaled up.
void Canvas::text(int x, int y, const std::string& s, Rgb c) {
    std::vector<char> buffer(s.size() * 1024 + 256);  // a glyph takes up to ~14 quads of 64 bytes
    std::string copy = s;
    unsigned char colour[4] = {0, 0, 0, 255};
    const int quads = stb_easy_font_print(0, 0, copy.data(), colour, buffer.data(), static_cast<int>(buffer.size()));
    const auto* v = reinterpret_cast<const float*>(buffer.data());
    for (int q = 0; q < quads; ++q) {
        const float* a = v + q * 16;  // 4 vertices of (x, y, z, rgba) = 4 floats each
        const float* d = a + 8;
        fill(x + static_cast<int>(a[0] * kTextScale), y + static_cast<int>(a[1] * kTextScale),
             x + static_cast<int>(d[0] * kTextScale), y + static_cast<int>(d[1] * kTextScale), c);
    }
}

int Canvas::textWidth(const std::string& s) {
    std::string copy = s;
    return stb_easy_font_width(copy.data()) * kTextScale;
}

std::string Canvas::fitted(std::string s, int width) {
    if (textWidth(s) <= width) return s;
    while (!s.empty() && textWidth(s + "..") > width) s.pop_back();
    return s + "..";
}

void Canvas::blit(int x, int y, const Image& image) {
    for (int v = 0; v < image.height; ++v)
        for (int u = 0; u < image.width; ++u) {
            if (x + u < 0 || y + v < 0 || x + u >= m_image.width || y + v >= m_image.height) continue;
            for (int c = 0; c < 3; ++c) m_image.at(x + u, y + v, c) = image.at(u, v, image.channels == 1 ? 0 : c);
        }
}

}  // namespace btflut
