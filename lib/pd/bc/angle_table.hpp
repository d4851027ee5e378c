// pd/bc/angle_table.hpp -- an axisymmetric surface load given at angles from the symmetry axis: the
// CFD pressure, shear and heat flux of a body in flight, given at points of its surface at angles
// phi from the flight direction (spec/000c sec. 4.1: 25 points, "cubic interpolation in angle, using
// the symmetry").
// Interpolation: the periodic cubic spline (GSL cspline_periodic) through the table and its mirror
// image phi -> 360 deg - phi. Symmetric data give a symmetric spline, so the load is smooth through
// the stagnation point (phi = 0) and the rear point (phi = 180 deg) with zero slope there, and a
// table need not hold those two angles.
// Reading one from a CSV file: io/angle_table_file.hpp.
#pragma once
#include <gsl/gsl_errno.h>
#include <gsl/gsl_spline.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace pd {

class AngleTable {
public:
    // angles [deg] strictly increasing within [0, 180], at least two; values finite.
    AngleTable(const std::vector<double>& angle_deg, const std::vector<double>& value)
    {
        if (angle_deg.size() != value.size()) throw std::invalid_argument("angle table: as many angles as values needed");
        if (angle_deg.size() < 2) throw std::invalid_argument("angle table: at least two angles needed");
        for (std::size_t k = 0; k < angle_deg.size(); ++k) {
            if (!(angle_deg[k] >= 0 && angle_deg[k] <= 180)) throw std::invalid_argument("angle table: angles must lie in [0, 180] deg");
            if (k > 0 && !(angle_deg[k] > angle_deg[k - 1])) throw std::invalid_argument("angle table: angles must increase strictly");
            if (!std::isfinite(value[k])) throw std::invalid_argument("angle table: values must be finite");
        }
        for (std::size_t k = 0; k < angle_deg.size(); ++k) x_.push_back(angle_deg[k]), y_.push_back(value[k]);
        for (std::size_t k = angle_deg.size(); k-- > 0;)  // the mirror image, 180 and 0 not doubled
            if (angle_deg[k] > 0 && angle_deg[k] < 180 && 360 - angle_deg[k] > x_.back()) x_.push_back(360 - angle_deg[k]), y_.push_back(value[k]);
        x_.push_back(x_.front() + 360), y_.push_back(y_.front());  // the period's end
        const std::size_t n = x_.size();
        if (n < 3) throw std::invalid_argument("angle table: at least two distinct angles needed");
        spline_.reset(gsl_spline_alloc(gsl_interp_cspline_periodic, n));
        gsl_error_handler_t* old = gsl_set_error_handler_off();
        const int status = gsl_spline_init(spline_.get(), x_.data(), y_.data(), n);
        gsl_set_error_handler(old);
        if (status != GSL_SUCCESS) throw std::invalid_argument("angle table: the spline could not be formed");
    }
    AngleTable(AngleTable&&) noexcept = default;
    AngleTable& operator=(AngleTable&&) noexcept = default;

    double min_value() const { return *std::min_element(y_.begin(), y_.end()); }  // of the table's values
    // The value at phi [rad] from the axis, phi in [0, pi] (folded into it otherwise).
    double operator()(double phi) const
    {
        double deg = std::fmod(std::abs(phi) * 180 / std::numbers::pi, 360.0);
        if (deg > 180) deg = 360 - deg;
        if (deg < x_.front()) deg += 360;
        gsl_interp_accel acc{};
        return gsl_spline_eval(spline_.get(), std::min(deg, x_.back()), &acc);
    }

private:
    struct Free { void operator()(gsl_spline* s) const { gsl_spline_free(s); } };
    std::vector<double> x_, y_;  // the extended table over one period [deg], [value]
    std::unique_ptr<gsl_spline, Free> spline_;
};

}  // namespace pd
