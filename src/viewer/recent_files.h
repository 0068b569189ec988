#pragma once
// The viewer's recently opened files: $XDG_CONFIG_HOME/btflut/recent.txt (else
// ~/.config/btflut/recent.txt), one absolute path per line, newest first, at most 10.

#include <string>
#include <vector>

namespace btflut {

/// The list; empty when there is none or it cannot be read.
std::vector<std::string> loadRecentFiles();

/// Puts `path` (made absolute) first and saves the list (atomically); a failure to save is
/// not an error worth stopping for, so it is only returned as false.
bool rememberRecentFile(const std::string& path);

}  // namespace btflut
