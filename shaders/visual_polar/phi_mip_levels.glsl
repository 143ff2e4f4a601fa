// Shared by phi_mips.comp (levels it skips) and unwarp_lookup.comp (the mip dispatches'
// indirect group counts: none for a level the mapping never reads). Needs VISUAL_POLAR_PARAMS.
// The highest level unwarp.comp can read: its level L is largest in the fovea, log2 of H rows
// over the fovea's circumference 2 pi r_f (beyond it n / 2 pi r <= H / 2 pi r_f); it reads
// floor(L) and floor(L) + 1. The smallest r_f of the eyes bounds both.
uint highestLevelRead(uint eyes) {
    float rFovea = 1e30;
    for (uint e = 0u; e < eyes; ++e) {
        VisualPolarMap me = vpMapOfEye(e);
        rFovea = min(rFovea, me.dMax * me.foveaDegrees / kVpMaxDegrees);
    }
    // dMax >= 0.5 and foveaDegrees >= 1e-3: rFovea > 0; the max() keeps log2 finite anyway.
    float L = log2(max(float(vp.grid.y) / max(2.0 * kVpPi * rFovea, 1e-6), 1.0));
    return uint(floor(L + 1e-3)) + 1u;  // a margin for rounding against unwarp.comp's L
}
