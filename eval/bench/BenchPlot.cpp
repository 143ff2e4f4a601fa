// The `fovea bench` plot: GPU frame time (x, ms) against error (y, RMSE %), one labelled point
// per graph, written as hand-made SVG (no plotting dependency; any browser shows it).
// Both axes start at 0 so distances between points read as ratios.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "eval/bench/Bench.h"

namespace fovea::eval {

namespace {

constexpr double kWidth = 720, kHeight = 480;
constexpr double kLeft = 80, kRight = 40, kTop = 56, kBottom = 64;
// Colour-blind-safe palette (Okabe and Ito 2008), cycled.
constexpr const char* kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                    "#E69F00", "#56B4E9", "#000000", "#F0E442"};

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string num(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", v);
    return text;
}

// Tick step of 1, 2 or 5 times a power of ten giving about 5 intervals up to `max`.
double tickStep(double max) {
    const double raw = max / 5.0;  // max > 0: callers pass a positive axis end
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (m * power >= raw) return m * power;
    return 10.0 * power;
}

// Axis end: the largest value plus 10%, rounded up to a tick; 1 when every value is 0 (or not
// finite), so the axis never has zero length.
double axisEnd(double maxValue) {
    if (!(maxValue > 0.0) || !std::isfinite(maxValue)) return 1.0;
    const double step = tickStep(maxValue * 1.1);
    return std::ceil(maxValue * 1.1 / step) * step;
}

std::string tickLabel(double v, double step) {
    const int decimals = step >= 1.0 ? 0 : int(std::ceil(-std::log10(step)));
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", decimals, v);
    return text;
}

}  // namespace

namespace {

// Splits a title into at most two lines of about `width` characters at spaces (a long bench name
// plus the device would run off the picture); a longer rest ends in "...".
// `truncated`: the second line was cut short (the caller appends "...").
std::vector<std::string> titleLines(const std::string& title, size_t width, bool& truncated) {
    truncated = false;
    if (title.size() <= width) return {title};
    size_t cut = title.rfind(' ', width);
    if (cut == std::string::npos || cut == 0) cut = width;
    std::vector<std::string> lines{title.substr(0, cut)};
    std::string_view rest(title);
    rest.remove_prefix(std::min(title.size(), cut + 1));
    if (rest.size() <= width) {
        lines.emplace_back(rest);
    } else {
        lines.emplace_back(rest.substr(0, width - 3));
        truncated = true;
    }
    return lines;
}

}  // namespace

std::string benchPlotSvg(const std::vector<BenchResult>& results, const std::string& title) {
    double maxMs = 0, maxErr = 0;
    for (const auto& r : results) {
        maxMs = std::max(maxMs, r.frameMs.median);
        maxErr = std::max(maxErr, r.meanErrors.rmsePercent);
    }
    const double xEnd = axisEnd(maxMs), yEnd = axisEnd(maxErr);
    const double plotW = kWidth - kLeft - kRight, plotH = kHeight - kTop - kBottom;
    auto px = [&](double v) { return kLeft + v / xEnd * plotW; };              // xEnd > 0
    auto py = [&](double v) { return kHeight - kBottom - v / yEnd * plotH; };  // yEnd > 0
    std::ostringstream s;
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
      << "\" viewBox=\"0 0 " << kWidth << " " << kHeight
      << "\" font-family=\"Helvetica, Arial, sans-serif\" font-size=\"13\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    // About 8 px per character at 14 px: 84 characters fit the 720 px width with a margin.
    bool truncated = false;
    const auto lines = titleLines(title, 84, truncated);
    for (size_t i = 0; i < lines.size(); ++i)
        s << "<text x=\"" << kWidth / 2 << "\" y=\"" << (lines.size() == 1 ? 30 : 20 + 18 * i)
          << "\" text-anchor=\"middle\" font-size=\"14\">" << escape(lines[i])
          << (truncated && i + 1 == lines.size() ? "..." : "") << "</text>\n";
    // Grid, ticks and tick labels.
    const double xStep = tickStep(xEnd), yStep = tickStep(yEnd);
    for (double v = 0; v <= xEnd + xStep * 1e-6; v += xStep)
        s << "<line x1=\"" << num(px(v)) << "\" y1=\"" << kTop << "\" x2=\"" << num(px(v))
          << "\" y2=\"" << kHeight - kBottom + 6 << "\" stroke=\"#e0e0e0\"/>\n"
          << "<text class=\"xtick\" x=\"" << num(px(v)) << "\" y=\"" << kHeight - kBottom + 22
          << "\" text-anchor=\"middle\">" << tickLabel(v, xStep) << "</text>\n";
    for (double v = 0; v <= yEnd + yStep * 1e-6; v += yStep)
        s << "<line x1=\"" << kLeft - 6 << "\" y1=\"" << num(py(v)) << "\" x2=\"" << kWidth - kRight
          << "\" y2=\"" << num(py(v)) << "\" stroke=\"#e0e0e0\"/>\n"
          << "<text class=\"ytick\" x=\"" << kLeft - 10 << "\" y=\"" << num(py(v) + 4)
          << "\" text-anchor=\"end\">" << tickLabel(v, yStep) << "</text>\n";
    // Axes and their titles.
    s << "<line x1=\"" << kLeft << "\" y1=\"" << kHeight - kBottom << "\" x2=\"" << kWidth - kRight
      << "\" y2=\"" << kHeight - kBottom << "\" stroke=\"black\"/>\n"
      << "<line x1=\"" << kLeft << "\" y1=\"" << kTop << "\" x2=\"" << kLeft << "\" y2=\""
      << kHeight - kBottom << "\" stroke=\"black\"/>\n"
      << "<text x=\"" << kLeft + plotW / 2 << "\" y=\"" << kHeight - 18
      << "\" text-anchor=\"middle\">GPU frame time, median (ms)</text>\n"
      << "<text x=\"22\" y=\"" << kTop + plotH / 2
      << "\" text-anchor=\"middle\" transform=\"rotate(-90 22 " << kTop + plotH / 2
      << ")\">error against the reference, RMSE (%)</text>\n";
    // The Pareto front (BenchResult::pareto): a staircase through the optimal points in order of
    // time - everything above and right of it is beaten by a point on it - and a ring on each.
    std::vector<const BenchResult*> front;
    for (const auto& r : results)
        if (r.pareto) front.push_back(&r);
    std::sort(front.begin(), front.end(), [](const BenchResult* a, const BenchResult* b) {
        return a->frameMs.median < b->frameMs.median;
    });
    if (!front.empty()) {
        s << "<polyline class=\"pareto-front\" fill=\"none\" stroke=\"#555555\" "
             "stroke-dasharray=\"5 4\" points=\"";
        for (size_t i = 0; i < front.size(); ++i) {
            const double x = px(front[i]->frameMs.median), y = py(front[i]->meanErrors.rmsePercent);
            if (i > 0) s << num(x) << "," << num(py(front[i - 1]->meanErrors.rmsePercent)) << " ";
            s << num(x) << "," << num(y) << " ";
        }
        s << "\"/>\n";
        for (const BenchResult* r : front)
            s << "<circle class=\"pareto\" cx=\"" << num(px(r->frameMs.median)) << "\" cy=\""
              << num(py(r->meanErrors.rmsePercent))
              << "\" r=\"10\" fill=\"none\" stroke=\"#555555\" stroke-width=\"1.5\"></circle>\n";
        s << "<text x=\"" << kWidth - kRight << "\" y=\"" << kTop - 6
          << "\" text-anchor=\"end\" font-size=\"12\" fill=\"#555555\">ringed, dashed: Pareto "
             "front (faster or more accurate than every other point)</text>\n";
    }
    // One point per graph; labels alternate above and below to keep close points readable.
    for (size_t i = 0; i < results.size(); ++i) {
        const auto& r = results[i];
        const double x = px(r.frameMs.median), y = py(r.meanErrors.rmsePercent);
        const char* colour = kColours[i % std::size(kColours)];
        const bool right = x < kLeft + plotW * 0.75;  // labels of points near the right edge
        s << "<circle class=\"point\" cx=\"" << num(x) << "\" cy=\"" << num(y)
          << "\" r=\"6\" fill=\"" << colour << "\"><title>" << escape(r.graph.label) << ": "
          << num(r.frameMs.median) << " ms, RMSE " << num(r.meanErrors.rmsePercent)
          << " %</title></circle>\n"
          << "<text class=\"label\" x=\"" << num(x + (right ? 10 : -10)) << "\" y=\""
          << num(y + (i % 2 ? 18 : -9)) << "\" text-anchor=\"" << (right ? "start" : "end")
          << "\" fill=\"" << colour << "\">" << escape(r.graph.label) << "</text>\n";
    }
    s << "</svg>\n";
    return s.str();
}

}  // namespace fovea::eval
