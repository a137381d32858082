#pragma once
// printf-style formatting into a std::string, with the compiler checking the arguments against
// the pattern (-Wformat): the tables and summaries of the profile are mostly numbers with units.
#include <string>

namespace sample_game {

[[gnu::format(printf, 1, 2)]] std::string formatted(const char* pattern, ...);

}  // namespace sample_game
