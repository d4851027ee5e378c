// Temperature-dependent material properties p(theta) (spec/000a sec. 3.9; seed 000a sec. 3.8).
// A Property is a small value type, one of
//   constant    p(theta) = v
//   piecewise   intervals [lo_b, hi_b) in increasing order, each with its own formula (any callable:
//               polynomial, rational, ...); the last interval also contains its upper end hi
//   table       points (theta_k, p_k), theta strictly increasing, linear interpolation between them
// max_over(a, b) bounds p on [a, b] (used for the explicit critical step with k(theta)): exact for a
// constant and a table (the values at a, b and the table points inside); for a piecewise property the
// maximum of p at the branch ends inside [a, b] and at 1001 evenly spaced points (exact for branches
// that are monotone, as the EN 1993-1-2 laws are; a sampled estimate otherwise).
// Outside [lo, hi] a piecewise or table property either clamps (the value at the nearest end, the
// default) or throws std::out_of_range (OutOfRange::error). A constant has no range.
// The source writes these as run-time compiled strings; here they are C++ callables.
//
// en1993_carbon_steel_specific_heat: EN 1993-1-2 eq. (3.36) of seed 000a, c [J/(kg K)] of carbon
// steel for 20 C <= theta <= 1200 C, with erratum E14 (linear coefficient 7.73e-1, not the printed
// 7.33e-1):
//   c = 425 + 7.73e-1 theta - 1.69e-3 theta^2 + 2.22e-6 theta^3     20 <= theta < 600
//   c = 666 + 13002 / (738 - theta)                                600 <= theta < 735
//   c = 545 + 17820 / (theta - 731)                                735 <= theta < 900
//   c = 650                                                        900 <= theta <= 1200
// (theta in C). Its peak c(735) = 5000 is the ferrite-austenite transition. Outside 20..1200 C it
// clamps (c(20) = 439.80 below, 650 above) unless OutOfRange::error is asked for.
//
// en1993_carbon_steel_conductivity: EN 1993-1-2 (2005) sec. 3.4.1.3 eq. (3.13), thermal conductivity
// lambda_a [W/(m K)] of carbon steel (not in the seeds or spec/000a, which give only c(theta)):
//   lambda_a = 54 - 3.33e-2 theta     20 <= theta < 800
//   lambda_a = 27.3                   800 <= theta <= 1200
// (theta in C; the code's own jump at 800 C is 27.36 -> 27.3). Clamps outside 20..1200 C by default.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pd {

enum class OutOfRange { clamp, error };

class Property {
public:
    struct Branch {
        double lo, hi;                          // interval [lo, hi) of the argument
        std::function<double(double)> formula;  // p on that interval
    };

    static Property constant(double v)
    {
        Property p;
        p.kind_ = Kind::constant;
        p.value_ = v;
        return p;
    }

    static Property piecewise(std::vector<Branch> branches, OutOfRange policy = OutOfRange::clamp)
    {
        if (branches.empty()) throw std::invalid_argument("Property::piecewise: no branch");
        for (std::size_t b = 0; b < branches.size(); ++b) {
            if (!(branches[b].lo < branches[b].hi)) throw std::invalid_argument("Property::piecewise: empty interval");
            if (b > 0 && branches[b].lo != branches[b - 1].hi)
                throw std::invalid_argument("Property::piecewise: intervals must be contiguous and increasing");
            if (!branches[b].formula) throw std::invalid_argument("Property::piecewise: branch without formula");
        }
        Property p;
        p.kind_ = Kind::piecewise;
        p.branches_ = std::move(branches);
        p.policy_ = policy;
        return p;
    }

    static Property table(std::vector<double> theta, std::vector<double> value, OutOfRange policy = OutOfRange::clamp)
    {
        if (theta.size() < 2 || theta.size() != value.size())
            throw std::invalid_argument("Property::table: need at least two (theta, value) pairs of equal count");
        for (std::size_t k = 1; k < theta.size(); ++k)
            if (!(theta[k] > theta[k - 1])) throw std::invalid_argument("Property::table: theta must increase strictly");
        Property p;
        p.kind_ = Kind::table;
        p.theta_ = std::move(theta);
        p.table_ = std::move(value);
        p.policy_ = policy;
        return p;
    }

    // Range of validity [lo, hi] (infinite for a constant).
    double lo() const { return kind_ == Kind::piecewise ? branches_.front().lo : kind_ == Kind::table ? theta_.front() : -1e308; }
    double hi() const { return kind_ == Kind::piecewise ? branches_.back().hi : kind_ == Kind::table ? theta_.back() : 1e308; }

    bool is_constant() const { return kind_ == Kind::constant; }

    // Largest value on [a, b] (see the file header for when it is exact).
    double max_over(double a, double b) const
    {
        if (a > b) std::swap(a, b);
        const Property& p = *this;
        double m = std::max(p(a), p(b));
        if (kind_ == Kind::table)
            for (double t : theta_)
                if (t > a && t < b) m = std::max(m, p(t));
        if (kind_ == Kind::piecewise) {
            for (const Branch& br : branches_)
                for (double t : {br.lo, std::nextafter(br.hi, br.lo)})
                    if (t > a && t < b) m = std::max(m, p(t));
            constexpr int samples = 1000;  // interior samples for non-monotone branches
            for (int s = 1; s < samples; ++s) m = std::max(m, p(a + (b - a) * s / samples));
        }
        return m;
    }

    double operator()(double theta) const
    {
        if (kind_ == Kind::constant) return value_;
        if (theta < lo() || theta > hi()) {
            if (policy_ == OutOfRange::error)
                throw std::out_of_range("Property: temperature " + std::to_string(theta) + " outside [" +
                                        std::to_string(lo()) + ", " + std::to_string(hi()) + "]");
            theta = std::clamp(theta, lo(), hi());
        }
        if (kind_ == Kind::piecewise) {
            // First branch with theta < hi; theta == hi of the last belongs to the last.
            auto it = std::upper_bound(branches_.begin(), branches_.end(), theta,
                                       [](double t, const Branch& b) { return t < b.hi; });
            if (it == branches_.end()) --it;
            return it->formula(theta);
        }
        // Table: the interval [theta_k, theta_k+1] holding theta, linear interpolation.
        std::size_t k = std::upper_bound(theta_.begin(), theta_.end(), theta) - theta_.begin();
        k = std::clamp<std::size_t>(k, 1, theta_.size() - 1);
        const double w = (theta - theta_[k - 1]) / (theta_[k] - theta_[k - 1]);
        return (1 - w) * table_[k - 1] + w * table_[k];
    }

private:
    enum class Kind { constant, piecewise, table };
    Kind kind_ = Kind::constant;
    double value_ = 0;
    std::vector<Branch> branches_;
    std::vector<double> theta_, table_;
    OutOfRange policy_ = OutOfRange::clamp;
};

// EN 1993-1-2 carbon-steel specific heat [J/(kg K)] of theta [C], seed 000a eq. (3.36) with erratum
// E14; valid 20..1200 C (see the file header for the branches and the out-of-range policy).
inline Property en1993_carbon_steel_specific_heat(OutOfRange policy = OutOfRange::clamp)
{
    constexpr double a0 = 425, a1 = 7.73e-1, a2 = -1.69e-3, a3 = 2.22e-6;  // cubic branch (E14: a1)
    return Property::piecewise(
        {{20, 600, [=](double t) { return a0 + t * (a1 + t * (a2 + t * a3)); }},
         {600, 735, [](double t) { return 666 + 13002 / (738 - t); }},  // rises to the alpha-gamma peak
         {735, 900, [](double t) { return 545 + 17820 / (t - 731); }},  // falls from the peak
         {900, 1200, [](double) { return 650.0; }}},
        policy);
}

// EN 1993-1-2 carbon-steel thermal conductivity [W/(m K)] of theta [C], eq. (3.13); valid 20..1200 C.
inline Property en1993_carbon_steel_conductivity(OutOfRange policy = OutOfRange::clamp)
{
    constexpr double a0 = 54, a1 = -3.33e-2, plateau = 27.3;  // [W/(m K)], [W/(m K^2)], [W/(m K)]
    return Property::piecewise({{20, 800, [=](double t) { return a0 + a1 * t; }}, {800, 1200, [=](double) { return plateau; }}},
                               policy);
}

}  // namespace pd
