// Captions on the rendered pictures: a 5 x 7 pixel bitmap font (capitals, digits and the
// punctuation numbers need), drawn on the CPU into the image the renderer read back.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace render {

// Pixels of one character cell at scale 1: 5 wide plus a column of space, 7 high plus two
// rows of space.
constexpr int kGlyphAdvance = 6, kGlyphLineHeight = 9;

// Draws `text` into RGBA8 pixels (rows top to bottom) with its top left corner at (x, y),
// each font pixel a `scale` x `scale` square, clipped to the image. Small letters are
// drawn as capitals; a character the font lacks as '?'.
void drawText(std::vector<std::uint8_t>& io_rgba, std::uint32_t width, std::uint32_t height, int x, int y, std::string_view text,
              int scale, const std::uint8_t (&colour)[3]);

// The lines on a dark band across the top of the image, scaled up on pictures wide enough
// to be read at a glance; a line too long for the image is cut at its right edge.
void drawCaption(std::vector<std::uint8_t>& io_rgba, std::uint32_t width, std::uint32_t height, std::span<const std::string> lines);

}  // namespace render
