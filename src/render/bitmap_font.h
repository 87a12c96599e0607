#pragma once
// A 5×7 pixel font for labels in PNG plots (digits, letters, common punctuation; lower case drawn as upper case).
#include <array>
#include <cstdint>

namespace quadcover {

/// Rows of the glyph of `c` from the top, bit 4 = leftmost column; all zero for unknown characters and space.
/// \pre none (a character without a glyph is blank).
std::array<std::uint8_t, 7> glyph_5x7(char c);

}  // namespace quadcover
