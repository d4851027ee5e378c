// Crack metrics on a damage field phi_i (critical_stretch.hpp, spec/002 eq. 2.17) in 2D.
// - Tip (spec/002 sec. 3.5, after Ha & Bobaru 2010): the damaged node (phi >= 0.35) farthest along
//   a propagation direction (tip_along) or farthest from a point (tip_farthest), in the reference
//   configuration; an optional mask restricts the candidates (one branch, one notch).
// - Speed (spec/002 eq. 6.1): V = |x_l - x_{l-1}| / (t_l - t_{l-1}) between tip samples one time
//   window apart (2 us in the branching test, 1.82 us in Kalthoff-Winkler); consecutive windows
//   do not overlap. Mean speed over [t_a, t_b] = tip path length over the windows in it / time.
// - Initiation: first sample whose tip advance exceeds the first sample's by min_advance.
// - Sections: damaged nodes are binned along dir (s = (x - origin).dir, bins of width h centred on
//   k h) and, within a bin, split into clusters along the normal n = (x - origin).perp wherever
//   two consecutive normal coordinates differ by more than gap (default 1.5 h: at least one
//   undamaged lattice row between two clusters).
// - Branching rule: the first bin at or beyond s_begin from which `confirm` consecutive bins all
//   hold two or more clusters (so an arrested side crack shorter than confirm bins is not a
//   branch). The outermost clusters of each such bin (up to `fit` bins) give the two branch
//   centrelines n = a + b s (least squares); the branch point is their intersection when it lies
//   between the last single-band bin minus `fit` bins and the split bin, otherwise the centre of
//   the last single-band bin. Branch angles atan(b) are measured from dir.
// - Connected crack: the nodes with phi >= a walk threshold reachable from seed nodes (the
//   pre-crack band) through such nodes, stepping along bonds no longer than a given length (a
//   breadth-first search); damage that nucleates apart from the crack (at a free edge) is then
//   not taken for its tip. The walk threshold may lie below the tip threshold: a running crack's
//   band has nodes with phi between 0.2 and 0.35 where it turns across the lattice.
// - Crack angle: principal axis (total least squares) of a node set, angle from the x axis.
// - Path deviation from a reference line (origin, dir): the crack centreline is the mean normal
//   coordinate of the damaged nodes of each bin in [s_begin, s_end]; its RMS and max |n|, and the
//   slope angle of its least-squares line.
// - Crack path as a level curve of phi (seed 001 uses 0.41): crack_path.hpp, included here.
#pragma once
#include "pd/core/bonds.hpp"
#include "problems/common/crack/crack_path.hpp"
#include "pd/core/field.hpp"
#include "pd/core/state_archive.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace pd::crack {

inline constexpr double tip_threshold = 0.35;  // damage of a tip node (spec/002 sec. 3.5) [-]
inline constexpr double path_level = 0.41;     // level curve of the crack path (seed 001) [-]
inline constexpr double nan = std::numeric_limits<double>::quiet_NaN();

using Mask = std::vector<std::uint8_t>;  // per node, 1 = candidate; empty = every node

struct Tip {
    int node = -1;       // -1: no damaged node
    Vec<2> x{};          // reference position [m]
    double advance = nan;  // (x - origin).dir or |x - origin| [m]
};

namespace detail {
template <class Score>
Tip best_damaged(const Field<2>& x, const std::vector<double>& phi, double threshold, const Mask& mask, Score&& score)
{
    Tip tip;
    for (std::size_t i = 0; i < phi.size(); ++i) {
        if (phi[i] < threshold || (!mask.empty() && !mask[i])) continue;
        const double s = score(x[i]);
        if (tip.node < 0 || s > tip.advance) tip = {static_cast<int>(i), x[i], s};
    }
    return tip;
}
inline Vec<2> perp(const Vec<2>& d) { return Vec<2>{{-d[1], d[0]}}; }
inline Vec<2> unit(const Vec<2>& d)
{
    const double n = norm(d);
    if (!(n > 0)) throw std::invalid_argument("crack metrics: direction must be non-zero");
    return (1 / n) * d;
}
// Least-squares line y = a + b x; returns {a, b} (b = nan for fewer than 2 distinct x).
inline std::pair<double, double> line_fit(const std::vector<double>& x, const std::vector<double>& y)
{
    const double n = static_cast<double>(x.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t k = 0; k < x.size(); ++k) sx += x[k], sy += y[k], sxx += x[k] * x[k], sxy += x[k] * y[k];
    const double den = n * sxx - sx * sx;
    if (x.size() < 2 || !(std::abs(den) > 0)) return {x.empty() ? nan : sy / n, nan};
    const double b = (n * sxy - sx * sy) / den;
    return {(sy - b * sx) / n, b};
}
}  // namespace detail

// Damaged node farthest along the unit direction dir from origin.
inline Tip tip_along(const Field<2>& x, const std::vector<double>& phi, const Vec<2>& origin, const Vec<2>& dir,
                     double threshold = tip_threshold, const Mask& mask = {})
{
    const Vec<2> d = detail::unit(dir);
    return detail::best_damaged(x, phi, threshold, mask, [&](const Vec<2>& p) { return dot(p - origin, d); });
}

// Damaged node farthest from origin.
inline Tip tip_farthest(const Field<2>& x, const std::vector<double>& phi, const Vec<2>& origin,
                        double threshold = tip_threshold, const Mask& mask = {})
{
    return detail::best_damaged(x, phi, threshold, mask, [&](const Vec<2>& p) { return norm(p - origin); });
}

// Mask of the nodes (phi >= threshold) connected to the seed nodes (see header); candidates
// restrict the search (empty = all nodes). step: largest bond length walked [m].
inline Mask connected_damage(const Bonds& bonds, const std::vector<double>& phi, const Mask& seeds, double step,
                             double threshold = tip_threshold, const Mask& candidates = {})
{
    Mask reached(phi.size(), 0);
    std::vector<int> queue;
    auto ok = [&](std::size_t i) { return phi[i] >= threshold && (candidates.empty() || candidates[i]); };
    for (std::size_t i = 0; i < phi.size(); ++i)
        if (seeds[i] && ok(i)) reached[i] = 1, queue.push_back(static_cast<int>(i));
    for (std::size_t q = 0; q < queue.size(); ++q) {
        const int i = queue[q];
        for (std::int64_t k = bonds.begin(i); k < bonds.end(i); ++k) {
            const int j = bonds.partner[k];
            if (!reached[j] && bonds.length[k] <= step && ok(j)) reached[j] = 1, queue.push_back(j);
        }
    }
    return reached;
}

struct SpeedSample {
    double t = 0;  // window midpoint [s]
    double v = 0;  // speed [m/s]
};

// Tip samples in time order.
struct TipHistory {
    std::vector<double> t;        // [s]
    std::vector<Vec<2>> x;        // tip positions [m]
    std::vector<double> advance;  // [m]

    void push(double time, const Tip& tip)
    {
        if (tip.node < 0) return;
        if (!t.empty() && !(time > t.back())) throw std::invalid_argument("TipHistory: times must increase");
        t.push_back(time), x.push_back(tip.x), advance.push_back(tip.advance);
    }
    std::size_t size() const { return t.size(); }
    void state(StateArchive& ar, const std::string& name) { ar(name + ".t", t), ar(name + ".x", x), ar(name + ".advance", advance); }

    // First time the advance exceeds the first sample's by min_advance [m]; nan if never.
    double initiation_time(double min_advance) const
    {
        for (std::size_t l = 1; l < t.size(); ++l)
            if (advance[l] >= advance[0] + min_advance) return t[l];
        return nan;
    }
    // First time the advance reaches a [m], linear between samples; nan if never.
    double time_at_advance(double a) const
    {
        if (t.empty()) return nan;
        if (advance[0] >= a) return t[0];
        for (std::size_t l = 1; l < t.size(); ++l)
            if (advance[l] >= a) return t[l - 1] + (t[l] - t[l - 1]) * (a - advance[l - 1]) / (advance[l] - advance[l - 1]);
        return nan;
    }
    // Samples one window apart: the first sample, then the first sample at or after each
    // previous one + window.
    std::vector<std::size_t> window_samples(double window) const
    {
        if (!(window > 0)) throw std::invalid_argument("crack speed: window must be positive");
        std::vector<std::size_t> idx;
        if (t.empty()) return idx;
        idx.push_back(0);
        for (std::size_t l = 1; l < t.size(); ++l)
            if (t[l] >= t[idx.back()] + window * (1 - 1e-9)) idx.push_back(l);  // 1e-9: sample times carry round-off
        return idx;
    }
    // Speed (6.1) over consecutive windows.
    std::vector<SpeedSample> speed(double window) const
    {
        const std::vector<std::size_t> idx = window_samples(window);
        std::vector<SpeedSample> v;
        for (std::size_t k = 1; k < idx.size(); ++k) {
            const std::size_t a = idx[k - 1], b = idx[k];
            v.push_back({0.5 * (t[a] + t[b]), norm(x[b] - x[a]) / (t[b] - t[a])});
        }
        return v;
    }
    // Tip path length over the windows inside [t_a, t_b] divided by their duration; nan if none.
    double mean_speed(double window, double t_a, double t_b) const
    {
        const std::vector<std::size_t> idx = window_samples(window);
        double path = 0, time = 0;
        for (std::size_t k = 1; k < idx.size(); ++k) {
            const std::size_t a = idx[k - 1], b = idx[k];
            if (t[a] < t_a - 1e-15 || t[b] > t_b + 1e-15) continue;  // 1e-15 s: round-off of accumulated times
            path += norm(x[b] - x[a]), time += t[b] - t[a];
        }
        return time > 0 ? path / time : nan;
    }
    double max_speed(double window) const
    {
        double vmax = nan;
        for (const SpeedSample& s : speed(window)) vmax = std::isnan(vmax) ? s.v : std::max(vmax, s.v);
        return vmax;
    }
};

// Clusters of damaged nodes in the bins along dir (see header).
struct Sections {
    double h = 0;  // bin width [m]
    std::map<long, std::vector<std::vector<double>>> bins;  // bin k (s = k h) -> clusters of normal coordinates [m]

    Sections(const Field<2>& x, const std::vector<double>& phi, const Vec<2>& origin, const Vec<2>& dir, double h,
             double threshold = tip_threshold, const Mask& mask = {}, double gap = nan)
        : h(h)
    {
        if (!(h > 0)) throw std::invalid_argument("crack sections: bin width h must be positive");
        const Vec<2> d = detail::unit(dir), p = detail::perp(d);
        if (std::isnan(gap)) gap = 1.5 * h;
        std::map<long, std::vector<double>> normals;
        for (std::size_t i = 0; i < phi.size(); ++i) {
            if (phi[i] < threshold || (!mask.empty() && !mask[i])) continue;
            const Vec<2> r = x[i] - origin;
            normals[std::lround(dot(r, d) / h)].push_back(dot(r, p));
        }
        for (auto& [k, n] : normals) {
            std::sort(n.begin(), n.end());
            auto& clusters = bins[k];
            clusters.push_back({n[0]});
            for (std::size_t q = 1; q < n.size(); ++q) {
                if (n[q] - n[q - 1] > gap) clusters.emplace_back();
                clusters.back().push_back(n[q]);
            }
        }
    }
    std::size_t clusters(long k) const
    {
        const auto it = bins.find(k);
        return it == bins.end() ? 0 : it->second.size();
    }
    static double mean(const std::vector<double>& v)
    {
        double s = 0;
        for (double e : v) s += e;
        return s / static_cast<double>(v.size());
    }
};

struct Branching {
    bool found = false;
    Vec<2> point{};          // branch point [m]
    double s = nan;          // its coordinate along dir from origin [m]
    double s_split = nan;    // first bin with two confirmed branches [m]
    double angle_upper = nan, angle_lower = nan;  // branch directions from dir (upper: +perp side) [rad]
};

struct BranchRule {
    double threshold = tip_threshold;  // damaged node [-]
    double gap = nan;                  // cluster gap [m]; nan = 1.5 h
    int confirm = 4;                   // consecutive two-cluster bins for a branch
    int fit = 10;                      // bins used by the branch line fits
};

inline Branching find_branching(const Field<2>& x, const std::vector<double>& phi, const Vec<2>& origin, const Vec<2>& dir,
                                double h, double s_begin, const BranchRule& rule = {}, const Mask& mask = {})
{
    const Vec<2> d = detail::unit(dir), p = detail::perp(d);
    const Sections sec(x, phi, origin, d, h, rule.threshold, mask, rule.gap);
    Branching br;
    if (sec.bins.empty()) return br;
    const long k_end = sec.bins.rbegin()->first;
    long k_split = 0;
    bool found = false;
    for (long k = std::lround(std::ceil(s_begin / h)); k + rule.confirm - 1 <= k_end && !found; ++k) {
        found = true;
        for (long q = k; q < k + rule.confirm; ++q) found = found && sec.clusters(q) >= 2;
        if (found) k_split = k;
    }
    if (!found) return br;
    std::vector<double> s, up, low;
    for (long k = k_split; k < k_split + rule.fit && sec.clusters(k) >= 2; ++k) {
        const auto& c = sec.bins.at(k);
        s.push_back(k * h), low.push_back(Sections::mean(c.front())), up.push_back(Sections::mean(c.back()));
    }
    const auto [au, bu] = detail::line_fit(s, up);
    const auto [al, bl] = detail::line_fit(s, low);
    long k_single = k_split - 1;  // last bin before the split that holds exactly one band
    while (k_single > k_split - rule.fit && sec.clusters(k_single) != 1) --k_single;
    double sb = nan, nb = nan;
    if (bu - bl > 0) {
        sb = (al - au) / (bu - bl);
        nb = au + bu * sb;
    }
    if (!(sb >= (k_single - rule.fit) * h && sb <= k_split * h)) {
        sb = k_single * h;
        nb = sec.clusters(k_single) == 1 ? Sections::mean(sec.bins.at(k_single)[0]) : 0.5 * (au + al + (bu + bl) * sb);
    }
    br.found = true;
    br.s = sb, br.s_split = k_split * h;
    br.point = origin + sb * d + nb * p;
    br.angle_upper = std::atan(bu), br.angle_lower = std::atan(bl);
    return br;
}

// Angle of the principal axis of a point set from the x axis, in (-pi/2, pi/2] [rad].
inline double principal_angle(const std::vector<Vec<2>>& pts)
{
    if (pts.size() < 2) throw std::invalid_argument("principal_angle: needs at least two points");
    Vec<2> c{};
    for (const auto& q : pts) c += q;
    c *= 1.0 / static_cast<double>(pts.size());
    double sxx = 0, syy = 0, sxy = 0;
    for (const auto& q : pts) {
        const Vec<2> r = q - c;
        sxx += r[0] * r[0], syy += r[1] * r[1], sxy += r[0] * r[1];
    }
    double a = 0.5 * std::atan2(2 * sxy, sxx - syy);  // major axis of the scatter matrix
    if (a <= -std::numbers::pi / 2 + 1e-15) a += std::numbers::pi;  // 1e-15: keep -pi/2 on the +pi/2 side
    return a;
}

// Reference positions of the damaged nodes (phi >= threshold) in the mask.
inline std::vector<Vec<2>> damaged_points(const Field<2>& x, const std::vector<double>& phi, double threshold = tip_threshold,
                                          const Mask& mask = {})
{
    std::vector<Vec<2>> pts;
    for (std::size_t i = 0; i < phi.size(); ++i)
        if (phi[i] >= threshold && (mask.empty() || mask[i])) pts.push_back(x[i]);
    return pts;
}

struct PathDeviation {
    std::vector<double> s, n;  // centreline: coordinate along dir and mean normal offset [m]
    double rms = nan, max = nan;  // of |n| [m]
    double angle = nan;           // slope of the centreline fit from dir [rad]
};

inline PathDeviation path_deviation(const Field<2>& x, const std::vector<double>& phi, const Vec<2>& origin, const Vec<2>& dir,
                                    double h, double s_begin, double s_end, double threshold = tip_threshold, const Mask& mask = {})
{
    const Sections sec(x, phi, origin, dir, h, threshold, mask, std::numeric_limits<double>::infinity());  // one cluster per bin
    PathDeviation dev;
    double sum2 = 0, mx = 0;
    for (const auto& [k, c] : sec.bins) {
        const double s = k * h;
        if (s < s_begin - 1e-9 * h || s > s_end + 1e-9 * h) continue;  // 1e-9 h: round-off of the bin centres
        const double n = Sections::mean(c[0]);
        dev.s.push_back(s), dev.n.push_back(n);
        sum2 += n * n, mx = std::max(mx, std::abs(n));
    }
    if (dev.s.empty()) return dev;
    dev.rms = std::sqrt(sum2 / static_cast<double>(dev.s.size())), dev.max = mx;
    dev.angle = std::atan(detail::line_fit(dev.s, dev.n).second);
    return dev;
}

}  // namespace pd::crack
