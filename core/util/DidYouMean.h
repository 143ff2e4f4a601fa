// "Did you mean ...?" suggestions for misspelt names (fields, passes, parameters, flags).
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace fovea {

// Levenshtein edit distance (case-sensitive).
size_t editDistance(std::string_view a, std::string_view b);

// The closest candidate within a distance of max(2, len/3), or "" if none is close enough.
std::string closestMatch(std::string_view name, const std::vector<std::string>& candidates);

// " (did you mean 'x'?)" or "" — ready to append to an error message.
std::string didYouMean(std::string_view name, const std::vector<std::string>& candidates);

}  // namespace fovea
