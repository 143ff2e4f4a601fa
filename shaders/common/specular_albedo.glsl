// Pre-integrated specular reflectance of PathTrace's GGX lobe, E(F0, roughness, NoV) = F0 * scale
// + bias (core/shading/SpecularAlbedo.h: definition, integration, tests): the divisor of the
// specular signal (issue 26; seed 004 "Cooking specular denoiser": diffuse and specular signals
// are demodulated separately before filtering). The table is the storage buffer
// `specular_albedo_table` that the pass binds (bakedSpecularAlbedoTable()), not a constant array:
// lavapipe compiles a dynamically indexed 1024-entry constant for minutes.
#ifndef FOVEA_SPECULAR_ALBEDO_GLSL
#define FOVEA_SPECULAR_ALBEDO_GLSL

const int kSpecularAlbedoSize = 32;  // SpecularAlbedo.h kSpecularAlbedoSize

// Explicit binding 32 (after scene_data.glsl's 16-31): a shader that declares the table without
// using it (PathTrace with brdf = lambert) would otherwise leave it at binding 0 (scene_data.glsl).
layout(std430, binding = 32) readonly buffer SpecularAlbedoTable {
    vec2 terms[];  // row j (roughness j / 31) major, column i (NoV i / 31)
} specular_albedo_table;

// {scale, bias} at (nov, roughness), bilinear between the entries; NaN reads as 0 and values
// outside [0, 1] clamp, as lookupSpecularAlbedo() on the CPU.
vec2 specularAlbedoTerms(float nov, float roughness) {
    float x = (nov > 0.0 ? min(nov, 1.0) : 0.0) * float(kSpecularAlbedoSize - 1);
    float y = (roughness > 0.0 ? min(roughness, 1.0) : 0.0) * float(kSpecularAlbedoSize - 1);
    int x0 = min(int(x), kSpecularAlbedoSize - 2);
    int y0 = min(int(y), kSpecularAlbedoSize - 2);
    float fx = x - float(x0), fy = y - float(y0);
    int k = y0 * kSpecularAlbedoSize + x0;
    vec2 lo = mix(specular_albedo_table.terms[k], specular_albedo_table.terms[k + 1], fx);
    vec2 hi = mix(specular_albedo_table.terms[k + kSpecularAlbedoSize],
                  specular_albedo_table.terms[k + kSpecularAlbedoSize + 1], fx);
    return mix(lo, hi, fy);
}

// E = F0 * scale + bias per channel.
vec3 specularAlbedo(vec3 f0, float nov, float roughness) {
    vec2 t = specularAlbedoTerms(nov, roughness);
    return f0 * t.x + t.y;
}

#endif
