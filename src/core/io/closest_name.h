#pragma once
// "did you mean ...?": the known name nearest a misspelt one, for every error that names an
// unknown option, command or file key.

#include <string>
#include <vector>

namespace btflut {

/// The name of `names` nearest `word` by edit distance (a prefix of 3+ characters counts as
/// 1), or "" when none is within a third of the word's length (at least 2).
std::string closestName(const std::string& word, const std::vector<std::string>& names);

}  // namespace btflut
