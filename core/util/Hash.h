// A stable 64-bit FNV-1a hash of bytes, as 16 hex digits: the keys that tie results written apart
// to their inputs (a bench item to its bench file, a reference shard to its graph). Not
// cryptographic: it tells different inputs apart, it does not defend against forgery.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace fovea {

inline std::string fnv1aHex(std::string_view bytes) {
    uint64_t h = 1469598103934665603ull;
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    return hex;
}

}  // namespace fovea
