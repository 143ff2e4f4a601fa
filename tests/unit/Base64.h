// Standard base64 (RFC 4648, with padding) for the tests that write glTF files with data: URIs;
// the loader decodes them with scene::base64Decode.
#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace fovea::test {

inline std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* kAlphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const size_t n = std::min<size_t>(3, bytes.size() - i);  // n bytes give n + 1 characters
        uint32_t word = 0;
        for (size_t k = 0; k < 3; ++k) word = word << 8 | (k < n ? bytes[i + k] : 0u);
        for (size_t k = 0; k < 4; ++k) out += k <= n ? kAlphabet[(word >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

}  // namespace fovea::test
