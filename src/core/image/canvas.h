#pragma once
// Drawing into an RGB image for btflut's figures (histogram panels, contact sheets, charts):
// filled rectangles, lines, dots and text from stb_easy_font, scaled up. No plotting library.

#include <string>

#include "core/image/image.h"

namespace btflut {

struct Rgb {
    float r, g, b;
};

inline constexpr Rgb kInk{0.1f, 0.1f, 0.1f}, kAxisGrey{0.55f, 0.55f, 0.55f};

/// The i-th colour of a palette of eight distinct ones, cycling.
Rgb paletteColour(std::size_t i);

class Canvas {
public:
    static constexpr int kTextScale = 2;
    static constexpr int kTextHeight = 7 * kTextScale;

    /// White, `w` x `h`.
    Canvas(int w, int h);
    /// Pixels [x0, x1) x [y0, y1), clipped to the image.
    void fill(int x0, int y0, int x1, int y1, Rgb c);
    /// A line `thickness` pixels wide from (x0, y0) to (x1, y1).
    void line(double x0, double y0, double x1, double y1, Rgb c, int thickness = 2);
    /// A square dot of side `size` centred at (x, y).
    void dot(double x, double y, int size, Rgb c);
    /// Text with its top-left corner at (x, y).
    void text(int x, int y, const std::string& s, Rgb c);
    static int textWidth(const std::string& s);
    /// `s` shortened with ".." to at most `width` pixels of text.
    static std::string fitted(std::string s, int width);
    /// An image (grey or RGB) with its top-left corner at (x, y), clipped.
    void blit(int x, int y, const Image& image);
    int width() const { return m_image.width; }
    int height() const { return m_image.height; }
    Image take() { return std::move(m_image); }

private:
    Image m_image;
};

}  // namespace btflut
