// The PD heat equation of Conduction (conduction.hpp) integrated by CVODE BDF with the KLU sparse
// direct solver (time/cvode_bdf.hpp): y = theta, y' = (Q + s - h (theta - T_inf)) / rho c(theta),
// 0 on held nodes; Jacobian (A - diag h) / rho c with A the model's linear heat operator
// (exact for constant rho c, the lagged-rho-c approximation otherwise). Error control by CVODE's
// tolerances instead of a fixed step.
// A nonlinear model (k(theta), conductivity.hpp) gets the frozen-k operator A(theta) re-assembled at
// each Jacobian evaluation: an approximate Jacobian (it omits the terms dk/dtheta (theta_j - theta_i)),
// so CVODE's Newton iteration is a modified Newton one; its convergence test and error control are
// unchanged, only the iteration count per step may grow.
// CvodeField: the same as a TemperatureField (heat/temperature_field.hpp) with one CVODE output per
// thermal step; make_temperature_field builds the field of any of the three integrators.
#pragma once
#include "pd/heat/conduction.hpp"
#include "pd/heat/temperature_field.hpp"
#include "pd/time/cvode_bdf.hpp"

#include <memory>
#include <stdexcept>
#include <vector>

namespace pd {

template <class Model>
class HeatCvode {
public:
    HeatCvode(Conduction<Model>& heat, const Model& model, const Bonds& bonds, std::vector<double> theta0, double t0,
              const CvodeOptions& opt = {})
        : heat_(heat), A_(heat_operator(model, bonds))
    {
        if (heat.loads().fixed_at) throw std::invalid_argument("CVODE heat: time-dependent held temperatures (fixed_at) are not written");
        heat_.apply_fixed(theta0);
        theta_.resize(theta0.size());
        cvode_ = std::make_unique<CvodeBdf>(
            std::move(theta0), t0,
            [this](double, const double* y, double* ydot) {
                theta_.assign(y, y + theta_.size());
                heat_.heating(theta_, P_);
                for (std::size_t i = 0; i < theta_.size(); ++i) ydot[i] = heat_.held(i) ? 0.0 : P_[i] / heat_.rho_c(i, y[i]);
            },
            [this](double, const double* y, CvodeBdf::SparseRowMajor& J) {
                if constexpr (NonlinearHeat<Model>) {  // frozen-k operator at y
                    theta_.assign(y, y + theta_.size());
                    heat_.model().point_pass(heat_.bonds(), theta_);
                    A_ = heat_operator(heat_.model(), heat_.bonds());
                }
                J = A_;  // row-major copy
                for (int r = 0; r < J.outerSize(); ++r) {
                    const double scale = heat_.held(r) ? 0.0 : 1.0 / heat_.rho_c(r, y[r]);
                    for (CvodeBdf::SparseRowMajor::InnerIterator it(J, r); it; ++it) {
                        double v = it.value();
                        if (it.col() == r) v -= heat_.h(r);
                        it.valueRef() = v * scale;
                    }
                }
            },
            opt);
    }

    const std::vector<double>& advance(double t_out) { return cvode_->advance(t_out); }
    CvodeBdf& cvode() { return *cvode_; }
    CvodeStats stats() const { return cvode_->stats(); }

private:
    Conduction<Model>& heat_;
    CvodeBdf::SparseRowMajor A_;
    std::vector<double> theta_, P_;
    std::unique_ptr<CvodeBdf> cvode_;
};

// A temperature field integrated by CVODE BDF, with an output at the end of each thermal step;
// the solver starts at the first step from the field as it is then.
template <class Model>
class CvodeField : public ConductingField<Model> {
public:
    CvodeField(Model model, const Bonds& bonds, std::vector<double> rho_c, HeatLoads loads, std::vector<double> theta0, double dt_thermal = 0,
               const CvodeOptions& opt = {})
        : ConductingField<Model>(std::move(model), bonds, std::move(rho_c), std::move(loads), std::move(theta0), HeatIntegrator::cvode, dt_thermal),
          opt_(opt)
    {
        if (this->conduction().loads().fixed_at)
            throw std::invalid_argument("CVODE heat: time-dependent held temperatures (fixed_at) are not written");
    }
    const HeatCvode<Model>* solver() const { return cvode_.get(); }  // null before the first step
    // CVODE's own state would not see the change (its integrator would need a restart).
    void deposit(const std::vector<double>&) override
    {
        throw std::invalid_argument("CVODE heat: deposited heat (dissipation) is not written; use explicit or implicit Euler");
    }

protected:
    void take_step() override
    {
        if (!cvode_) cvode_ = std::make_unique<HeatCvode<Model>>(this->conduction(), this->model(), this->bonds(), this->theta, this->t(), opt_);
        this->theta = cvode_->advance(double(this->step + 1) * this->dt);
    }

private:
    CvodeOptions opt_;
    std::unique_ptr<HeatCvode<Model>> cvode_;
};

// The temperature field of `model` under the given integrator (heat/temperature_field.hpp).
template <class Model>
std::unique_ptr<ConductingField<Model>> make_temperature_field(Model model, const Bonds& bonds, std::vector<double> rho_c, HeatLoads loads,
                                                               std::vector<double> theta0, HeatIntegrator integrator, double dt_thermal = 0)
{
    if (integrator == HeatIntegrator::cvode)
        return std::make_unique<CvodeField<Model>>(std::move(model), bonds, std::move(rho_c), std::move(loads), std::move(theta0), dt_thermal);
    return std::make_unique<ConductingField<Model>>(std::move(model), bonds, std::move(rho_c), std::move(loads), std::move(theta0), integrator,
                                                    dt_thermal);
}

}  // namespace pd
