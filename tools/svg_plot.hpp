// tools/svg_plot.hpp -- a small SVG line/point chart: linear or logarithmic axes with ticks, axis
// labels (with units), one colour per series and a legend. Enough for the report index (convergence,
// work-precision, stability and history plots); no dependency beyond the standard library.
//
//     svg::Chart c{.title = "E1 vs dx", .xlabel = "dx [m]", .ylabel = "E1 [-]", .xlog = true, .ylog = true};
//     c.series.push_back({"LPS", {{0.1, 0.59}, {0.02, 0.14}}});
//     std::string text = c.render();  // <svg ...>...</svg>
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace svg {

// Text for SVG/HTML: & < > " escaped.
inline std::string escape(const std::string& s)
{
    std::string out;
    for (char ch : s) {
        if (ch == '&') out += "&amp;";
        else if (ch == '<') out += "&lt;";
        else if (ch == '>') out += "&gt;";
        else if (ch == '"') out += "&quot;";
        else out += ch;
    }
    return out;
}

inline std::string num(double v, const char* fmt = "%.1f")
{
    char b[64];
    std::snprintf(b, sizeof b, fmt, v);
    return b;
}

struct Series {
    std::string name;
    std::vector<std::pair<double, double>> points;  // (x, y), drawn in this order
    bool line = true, markers = true;
};

// One axis: the data range, linear or logarithmic, mapped onto [p0, p1] pixels.
struct Axis {
    double lo = 0, hi = 1;
    bool log = false;
    double p0 = 0, p1 = 1;

    double t(double v) const { return log ? std::log10(v) : v; }
    double pixel(double v) const { return p0 + (t(v) - t(lo)) / (t(hi) - t(lo)) * (p1 - p0); }
    // Tick values: decades (and 2, 5 within a decade when the range is short) on a log axis, steps
    // of 1, 2 or 5 x 10^k on a linear one.
    std::vector<double> ticks() const
    {
        std::vector<double> out;
        if (log) {
            const int a = static_cast<int>(std::floor(std::log10(lo))), b = static_cast<int>(std::ceil(std::log10(hi)));
            const bool fine = b - a <= 2;
            for (int k = a; k <= b; ++k)
                for (double m : fine ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
                    const double v = m * std::pow(10.0, k);
                    if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) out.push_back(v);
                }
            return out;
        }
        const double raw = (hi - lo) / 5, mag = std::pow(10.0, std::floor(std::log10(raw)));
        const double step = raw / mag < 1.5 ? mag : raw / mag < 3.5 ? 2 * mag : raw / mag < 7.5 ? 5 * mag : 10 * mag;
        for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) out.push_back(std::abs(v) < 1e-12 * step ? 0 : v);
        return out;
    }
    // Widens a degenerate range (one value); pads a linear range by 5 % on each side.
    void settle()
    {
        if (log) {
            if (!(hi > lo)) lo /= 2, hi *= 2;
            return;
        }
        if (!(hi > lo)) {
            const double d = lo == 0 ? 1 : std::abs(lo) * 0.1;
            lo -= d, hi += d;
        }
        const double pad = 0.05 * (hi - lo);
        lo -= pad, hi += pad;
    }
};

inline std::string tick_label(double v) { return v == 0 ? "0" : num(v, "%.3g"); }  // 1.5e-04, 2.5e-05: steps of 1, 2, 5 x 10^k

struct Chart {
    std::string title, xlabel, ylabel;  // labels carry their unit: "dx [m]"
    bool xlog = false, ylog = false;
    std::vector<Series> series;
    int width = 560, height = 360;

    std::string render() const
    {
        static const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2",
                                        "#7f7f7f", "#bcbd22"};
        Axis x{.lo = INFINITY, .hi = -INFINITY, .log = xlog, .p0 = 70, .p1 = width - 150.0};
        Axis y{.lo = INFINITY, .hi = -INFINITY, .log = ylog, .p0 = height - 50.0, .p1 = 30};
        for (const Series& s : series)
            for (const auto& [px, py] : s.points) {
                if (!std::isfinite(px) || !std::isfinite(py) || (xlog && px <= 0) || (ylog && py <= 0)) continue;
                x.lo = std::min(x.lo, px), x.hi = std::max(x.hi, px), y.lo = std::min(y.lo, py), y.hi = std::max(y.hi, py);
            }
        std::string o = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width) + "\" height=\"" +
                        std::to_string(height) + "\" viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) +
                        "\" font-family=\"sans-serif\" font-size=\"11\">\n";
        o += "<title>" + escape(title) + "</title>\n";
        o += "<text x=\"" + num(width / 2.0) + "\" y=\"16\" text-anchor=\"middle\" font-size=\"13\">" + escape(title) + "</text>\n";
        if (!(x.lo <= x.hi)) {  // nothing plottable
            o += "<text x=\"" + num(width / 2.0) + "\" y=\"" + num(height / 2.0) + "\" text-anchor=\"middle\">no finite data</text>\n";
            return o + axis_labels(x, y) + "</svg>\n";
        }
        x.settle(), y.settle();
        o += "<rect x=\"" + num(x.p0) + "\" y=\"" + num(y.p1) + "\" width=\"" + num(x.p1 - x.p0) + "\" height=\"" + num(y.p0 - y.p1) +
             "\" fill=\"none\" stroke=\"#444\"/>\n";
        for (double v : x.ticks()) {
            const double p = x.pixel(v);
            o += "<line x1=\"" + num(p) + "\" y1=\"" + num(y.p0) + "\" x2=\"" + num(p) + "\" y2=\"" + num(y.p1) + "\" stroke=\"#ddd\"/>\n";
            o += "<text x=\"" + num(p) + "\" y=\"" + num(y.p0 + 14) + "\" text-anchor=\"middle\">" + tick_label(v) + "</text>\n";
        }
        for (double v : y.ticks()) {
            const double p = y.pixel(v);
            o += "<line x1=\"" + num(x.p0) + "\" y1=\"" + num(p) + "\" x2=\"" + num(x.p1) + "\" y2=\"" + num(p) + "\" stroke=\"#ddd\"/>\n";
            o += "<text x=\"" + num(x.p0 - 4) + "\" y=\"" + num(p + 4) + "\" text-anchor=\"end\">" + tick_label(v) + "</text>\n";
        }
        o += axis_labels(x, y);
        for (std::size_t k = 0; k < series.size(); ++k) {
            const Series& s = series[k];
            const std::string colour = colours[k % 10];
            std::string path;
            for (const auto& [px, py] : s.points) {
                if (!std::isfinite(px) || !std::isfinite(py) || (xlog && px <= 0) || (ylog && py <= 0)) continue;
                path += (path.empty() ? "" : " ") + num(x.pixel(px)) + "," + num(y.pixel(py));
                if (s.markers)
                    o += "<circle cx=\"" + num(x.pixel(px)) + "\" cy=\"" + num(y.pixel(py)) + "\" r=\"2.5\" fill=\"" + colour + "\"/>\n";
            }
            if (s.line && !path.empty())
                o += "<polyline points=\"" + path + "\" fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"1.5\"/>\n";
            const double ly = y.p1 + 8 + 16.0 * static_cast<double>(k);
            o += "<line x1=\"" + num(x.p1 + 10) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(x.p1 + 28) + "\" y2=\"" + num(ly) + "\" stroke=\"" +
                 colour + "\" stroke-width=\"2\"/>\n";
            o += "<text x=\"" + num(x.p1 + 32) + "\" y=\"" + num(ly + 4) + "\">" + escape(s.name) + "</text>\n";
        }
        return o + "</svg>\n";
    }

private:
    std::string axis_labels(const Axis& x, const Axis& y) const
    {
        std::string o = "<text class=\"xlabel\" x=\"" + num((x.p0 + x.p1) / 2) + "\" y=\"" + num(height - 12.0) +
                        "\" text-anchor=\"middle\">" + escape(xlabel) + "</text>\n";
        const double cy = (y.p0 + y.p1) / 2;
        o += "<text class=\"ylabel\" x=\"16\" y=\"" + num(cy) + "\" text-anchor=\"middle\" transform=\"rotate(-90 16 " + num(cy) + ")\">" +
             escape(ylabel) + "</text>\n";
        return o;
    }
};

}  // namespace svg
