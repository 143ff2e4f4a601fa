// P1's theoretical foveation gain (seed 003 P1 §4, Koskela et al. 2016): the share of a display's
// samples a gaze-tracked renderer may omit because the eye cannot resolve them, and, for the same
// display, the samples fovea's three foveated layouts actually trace (docs/gain-model.md).
//
// The model (P1 §4): the acuity M(e) of P1 Eq. 2 (60 c/deg up to 5.79 degrees, 449.4 / (0.3 e +
// 1)^2 beyond), capped at the cycles per degree the display can show, integrated over the
// display's field of view as a solid of revolution around the gaze; the saving is 1 - that
// integral / (display cpd x FOV area). The gaze at the FOV centre gives P1's lower bound.
//
// Reading choices (docs/gain-model.md): area in flat polar (e, phi) degrees (P1 Fig. 5's solid
// of revolution, the polar sampling of P4 Eq. 2) and samples proportional to c/deg; the Vive's
// "circular area with radius of 110 degrees" is a 110-degree *diameter*: only that reproduces
// P1's 70 % (radius 110 gives 89 %). Solid angle and samples proportional to cpd^2 are options.
#pragma once
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace fovea::sampling {

// P1 Eq. 2 (after Reddy's model with G(0) = 1): M(e) in c/deg, e in degrees from the gaze.
inline constexpr double kAcuityPeakCpd = 60.0;
inline constexpr double kAcuityTailNumerator = 449.4;
// P1 Eq. 2 / P4 Eq. 1's knee; the same constant as kAcuityFlatDegrees (VisualPolar.h).
inline constexpr double kAcuityKneeDegrees = 5.79;
// Angular nodes of the polar quadrature (a periodic trapezoid rule, exponentially accurate for a
// smooth boundary, O(h^2) at the corners of a rectangle or where the boundary crosses a
// breakpoint of the integrand). 16384 keeps every preset's saving within 1e-7 (docs/gain-model.md)
// and one integral under a millisecond.
inline constexpr uint32_t kGainAngularSteps = 16384;
// The largest FOV per axis (degrees) and display cpd the model accepts.
inline constexpr double kMaxFovDegrees = 360.0;
inline constexpr double kMaxDisplayCpd = 1000.0;

// P1 Eq. 2.
double acuityCpd(double e);

enum class FovShape { Oval, Rectangle, Circle };
// How FOV area is measured: Flat = polar (e, phi) degrees, dA = e de dphi (P1's reading, the
// default); Solid = solid angle around the gaze, dA = sin(e) de dphi (in square degrees).
enum class AreaMeasure { Flat, Solid };
// Samples per unit area proportional to the detail: Linear = cpd (P1's reading, the default);
// Squared = cpd^2 (a 2D sample density for cpd along each axis).
enum class DetailDensity { Linear, Squared };

const char* toString(FovShape shape);
const char* toString(AreaMeasure measure);
const char* toString(DetailDensity density);

// A head-mounted display as P1 §4 describes one: the FOV in angle coordinates centred on the
// display (x right, y up), the detail it can show, and (for the layouts) its pixels per eye.
struct DisplayModel {
    double hfovDeg = 0, vfovDeg = 0;  // full horizontal and vertical FOV; Circle: equal
    FovShape shape = FovShape::Oval;
    double cpd = 0;                  // cycles per degree the display shows (> 0)
    uint32_t width = 0, height = 0;  // pixels per eye; 0 = not given
    glm::dvec2 gazeDeg{0.0, 0.0};    // gaze offset from the FOV centre, strictly inside the FOV
};

// Nyquist: two pixels per cycle, cpd = pixels / FOV degrees / 2, and its inverse (rounded, >= 1).
double nyquistCpd(uint32_t pixels, double fovDeg);
uint32_t nyquistPixels(double cpd, double fovDeg);

// P1 §4's two displays; nothing else is preset (the seed gives no other display's numbers).
struct DisplayPreset {
    const char* name;
    const char* source;  // where the numbers come from
    DisplayModel display;
    double reportedSaving;  // the saving P1 §4 reports for it (0.94, 0.70)
};
const std::vector<DisplayPreset>& displayPresets();
const DisplayPreset* findDisplayPreset(const std::string& name);  // null when unknown

struct GainOptions {
    AreaMeasure measure = AreaMeasure::Flat;
    DetailDensity density = DetailDensity::Linear;
    uint32_t angularSteps = kGainAngularSteps;  // rounded up to a multiple of 4, >= 16
};

struct GainResult {
    double required = 0;         // integral of min(M(e), cpd)^k dA (k = 1, or 2 for Squared)
    double full = 0;             // integral of cpd^k dA: every FOV point at the display's detail
    double area = 0;             // FOV area, square degrees (flat, or solid angle in deg^2)
    double relativeSamples = 0;  // required / full: the share that must still be traced
    double saving = 0;           // 1 - relativeSamples, in [0, 1]
    // max |saving(N) - saving(N / k)|, k = 2, 4, of the angular rule: an estimate of its error
    // (it covered the difference to a 16x finer rule in every case tested; not a proof).
    double errorEstimate = 0;
    // Beyond this eccentricity the display shows more than the eye resolves (M(e) < cpd); 0 when
    // it does everywhere (cpd > 60).
    double cutoffDeg = 0;
    double maxEccentricityDeg = 0;  // farthest FOV point from the gaze
};

// Throws InputError naming the field when the display cannot be evaluated: FOV not in
// (0, 360], Circle with unequal axes, cpd not in (0, 1000], gaze not strictly inside the FOV,
// Solid with a FOV point more than 180 degrees from the gaze.
void checkDisplay(const DisplayModel& display, AreaMeasure measure = AreaMeasure::Flat);

// P1 §4: the share of samples a display saves. Deterministic; well under 50 ms.
GainResult foveationGain(const DisplayModel& display, const GainOptions& options = {});

// The building block: the integral of f(|x - gaze|) over a shape with half extents `half`
// centred on the origin, `gaze` relative to that centre (strictly inside), in polar coordinates
// around the gaze. f is smooth between the sorted `breaks` (a jump or kink is allowed on one);
// the radial integral is exact up to rounding (8-point Gauss-Legendre on pieces at most
// 1/256 of the largest radius long), the angular one the trapezoid rule with `steps` nodes.
// Returns {integral, max |integral(steps) - integral(steps / k)|, k = 2, 4} (an error estimate).
glm::dvec2 integrateAroundGaze(FovShape shape, glm::dvec2 half, glm::dvec2 gaze,
                               const std::function<double(double)>& f,
                               const std::vector<double>& breaks, AreaMeasure measure,
                               uint32_t steps = kGainAngularSteps);

// --- what fovea's foveated layouts trace on one eye image ----------------------------------
// Every count is for the whole W x H eye image (fovea traces the rectangle, also the corners
// outside an oval FOV), with the gaze at `gazePx` (pixels, y down).
struct EyeImage {
    uint32_t width = 1, height = 1;
    glm::dvec2 gazePx{0.5, 0.5};
};
// The eye image of a display: its width/height, or nyquistPixels(cpd, FOV) where 0; the gaze
// mapped linearly from degrees to pixels (pixels evenly spread over the FOV's angles).
EyeImage eyeImageOf(const DisplayModel& display);

// Seed 000 §3.2 / Table 1 (FoveationMask): fovea d <= r0 (every pixel), middle r0 < d <= r1,
// outer beyond, with Table 1's 4 / 3 / 2 spp. Areas are the continuous ones (Table 1's are
// exactly pi r^2: 65144 = pi 144^2), so counts are expectations, not a rasterization.
inline constexpr double kPeresTable1R0 = 144.0, kPeresTable1R1 = 288.0;  // at 1080 rows
inline constexpr double kPeresTable1Rows = 1080.0;
inline constexpr uint32_t kPeresSpp[3] = {4, 3, 2};
struct PeresCounts {
    double r0 = 0, r1 = 0, outerProbability = 0.5;
    double area[3] = {0, 0, 0};     // pixels per layer (fovea, middle, outer)
    double sampled[3] = {0, 0, 0};  // expected sampled pixels under §3.2's toss
    double table1Samples = 0;       // Table 1's reading: every pixel, 4 / 3 / 2 spp
    double tossedSamples = 0;       // §3.2's reading: ramp 1 -> p in the middle, p outside
    double baseSamples = 0;         // seed 000 §4.2's Base: 4 spp at every pixel
};
PeresCounts peresCounts(const EyeImage& eye, double r0, double r1, double outerProbability);

// Seed 003 P5 (VisualPolarWarp with `traceOffscreen` false, a stereo side-by-side render):
// the VP grid of one eye, its valid texels and the texels whose centre falls on the screen.
struct VisualPolarCounts {
    double reduction = 0, foveaFraction = 0;
    uint32_t gridWidth = 0, gridHeight = 0;
    uint64_t validTexels = 0;   // inside the fovea clip
    uint64_t tracedTexels = 0;  // of those, centre on the eye image (double precision)
};
VisualPolarCounts visualPolarCounts(const EyeImage& eye, double reduction, double foveaFraction);

// Seed 003 P4's FV: `budget` samples per frame drawn with the radial density of m(e) = M(e) / 60
// (P4 Eq. 1-2) out to 80 degrees around the gaze, whatever the display.
struct FvCounts {
    double budget = 0;
    double insideFraction = 0;  // share of the samples landing inside the display's FOV
    double samplesInFov = 0;
    double frameFraction = 0;  // samplesInFov / (W H): the share of one 1-spp eye image
    double gazeSpp = 0;        // expected samples per pixel per frame at the gaze
};
FvCounts fvCounts(const DisplayModel& display, double budget);

}  // namespace fovea::sampling
