// problems/pd_run_heat.hpp -- the heat-conduction part of pd_run (issue 4): its options, their
// checks, and HeatRun: the library's temperature field of the point cloud (pd/heat/temperature_field.hpp;
// with mechanics, the scene's heat component) with pd_run's guard and heat.csv.
//   rho cv dT_i/dt = Q_i(T) + s on free nodes, T_i = T_fixed_i on held nodes (pd/heat/conduction.hpp),
//   Q from Agwai's bond-based model or the correspondence heat model (pd/heat/agwai.hpp,
//   correspondence_heat.hpp), s = --heat-source; no convection. The heat dissipated by plasticity or
//   viscosity (pd_run_dissipation.hpp) is added to T every --nsync-mh mechanical steps (pd/scene.hpp).
// Thermal expansion (--alpha, --T-ref): with mechanics, PMB, LPS (with SCF) and correspondence (linear
// law: the thermal strain; flanagan-taylor: its increment in each update) take the strain
// alpha (T - T_ref) of the run's temperatures (pd/models/thermal_expansion.hpp, correspondence.hpp), and
// so does the critical stretch of --s0; and PALS (per node, pals.hpp): every model of pd_run.
// --thermal-strain: a bond's free strain from its owner node (default, the source's rule) or the mean of
// its two ends (bond-mean: LPS, LPS+SCF, PALS; PMB takes the mean either way; correspondence refuses it).
// Integrators: explicit Euler, implicit Euler, CVODE BDF (one output per thermal step).
// dt_thermal default = 0.5 x the Gershgorin thermal critical step (spec/000b eq. 3.20).
// Clock: --dt-thermal, or --nsync-mk N: one thermal step of N mechanical steps (spec/000a 3.3.4).
// --heat-source s: a uniform volumetric source on the free points [W/m^3] (explicit, implicit Euler).
// Heat guard: with no sources the exact temperatures stay in the range of the initial and held
// values (maximum principle; with --heat-source s the range moves by s t/(rho cv), and its ceiling by
// the largest heat released at a point by each release of dissipated heat); a temperature
// outside that range widened by 10 x its width, or a non-finite one, throws pd::Unstable naming the
// thermal step and the node.
// Writes heat.csv: thermal_step,t_s,heat_J (sum rho cv V T),T_min,T_max.
#pragma once
#include "pd_run_checkpoint.hpp"
#include "pd/heat/agwai.hpp"
#include "pd/heat/conduction.hpp"
#include "pd/heat/correspondence_heat.hpp"
#include "pd/models/thermal_expansion.hpp"
#include "pd/time/heat_cvode.hpp"
#include "pd/core/state_archive.hpp"
#include "pd/io/csv.hpp"
#include "pd/io/options.hpp"
#include "pd/io/point_cloud.hpp"
#include "pd/time/verlet.hpp"  // pd::Unstable

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace pd_run {

constexpr double thermal_dt_safety = 0.5;  // margin below the Gershgorin bound, as for the mechanical step
constexpr double guard_widening = 10;      // the heat guard's band: the initial range widened 10 x its width

// The heat options as registered (references into pd::io::Options) and as used.
struct HeatOptions {
    const std::string& heat;
    const double &k, &cv, &T0, &dt;
    const int& steps;
    const std::string& integrator;
    const double& hourglass;
    const std::string& correction;
    const double &alpha, &T_ref;
    const std::string& thermal_strain;
    const int& nsync_mk;
    const double& source;
};

inline HeatOptions add_heat_options(pd::io::Options& opt, double automatic)
{
    return {opt.add_string("heat", "none", "heat conduction model (none: no temperature field)", {"none", "agwai", "correspondence"}),
            opt.add("k", automatic, "thermal conductivity (with --heat)", "W/(m K)"),
            opt.add("cv", automatic, "specific heat capacity (with --heat)", "J/(kg K)"),
            opt.add("T0", automatic, "initial temperature where the cloud has no T0 column (K or C, kept)", "K"),
            opt.add("dt-thermal", automatic, "thermal step (default 0.5 x thermal critical step)", "s"),
            opt.add_int("thermal-steps", 1000, "thermal steps of a --mechanics off run"),
            opt.add_string("thermal-integrator", "explicit", "heat integrator", {"explicit", "implicit", "cvode"}),
            opt.add("heat-hourglass", 0.0, "hourglass suppression coefficient of --heat correspondence"),
            opt.add_string("thermal-correction", "none", "Agwai thermal correction factor", {"none", "per-node", "pair-mean"}),
            opt.add("alpha", 0.0, "linear thermal expansion coefficient (with --heat and mechanics)", "1/K"),
            opt.add("T-ref", automatic, "stress-free temperature of --alpha (required with it)", "K"),
            opt.add_string("thermal-strain", "owner", "a bond's free thermal strain: its owner node's, or the mean of its ends",
                           {"owner", "bond-mean"}),
            opt.add_int("nsync-mk", 0, "mechanical steps per thermal step, N_sync(MK) (instead of --dt-thermal; with mechanics)"),
            opt.add("heat-source", 0.0, "uniform volumetric heat source on the free points (with --heat)", "W/m^3")};
}

// Cross-checks of the heat options; `mechanics` = the mechanical run is on. fail() never returns.
template <class Fail>
void check_heat_options(const pd::io::Options& opt, const HeatOptions& h, bool mechanics, Fail fail)
{
    const bool on = h.heat != "none";
    for (const char* name : {"k", "cv", "T0", "dt-thermal", "thermal-steps", "thermal-integrator", "heat-hourglass",
                             "thermal-correction", "alpha", "T-ref", "thermal-strain", "nsync-mk", "heat-source"})
        if (opt.given(name) && !on) fail(std::string("option --") + name + " needs --heat agwai|correspondence");
    if (!on) return;
    for (const char* name : {"k", "cv"})
        if (!opt.given(name)) fail(std::string("option --") + name + " is required with --heat");
    if (mechanics && opt.given("thermal-steps"))
        fail("option --thermal-steps applies to --mechanics off (with mechanics the heat follows the mechanical clock)");
    if (opt.given("heat-hourglass") && h.heat != "correspondence") fail("option --heat-hourglass applies to --heat correspondence only");
    if (opt.given("thermal-correction") && h.heat != "agwai") fail("option --thermal-correction applies to --heat agwai only");
    if (h.hourglass < 0) fail("option --heat-hourglass must be >= 0, got " + pd::io::format_double(h.hourglass));
    if (opt.given("nsync-mk")) {
        if (h.nsync_mk < 1) fail("option --nsync-mk must be >= 1, got " + std::to_string(h.nsync_mk));
        if (!mechanics) fail("option --nsync-mk needs the mechanics (not --mechanics off): it counts mechanical steps");
        if (opt.given("dt-thermal")) fail("options --nsync-mk and --dt-thermal exclude each other (both set the thermal step)");
    }
    if (!std::isfinite(h.source)) fail("option --heat-source must be finite");
    if (h.source != 0 && h.integrator == "cvode") fail("option --heat-source is written for --thermal-integrator explicit|implicit");
    for (const char* name : {"T-ref", "thermal-strain"})
        if (opt.given(name) && !opt.given("alpha")) fail(std::string("option --") + name + " needs --alpha");
    if (!opt.given("alpha")) return;
    if (!mechanics) fail("option --alpha needs the mechanics (not --mechanics off)");
    if (!opt.given("T-ref")) fail("option --T-ref is required with --alpha (the stress-free temperature)");
    if (!std::isfinite(h.alpha) || !std::isfinite(h.T_ref)) fail("options --alpha and --T-ref must be finite");
}

struct HeatSettings {
    std::string model, integrator;
    double k = 0, rho_cv = 0, T0 = 0, dt = 0, hourglass = 0, measure = 1;  // [W/(m K)], [J/(m^3 K)], [K], [s], [-], [m^(3-D)]
    pd::ThermalCorrection correction = pd::ThermalCorrection::none;
    long every = 1;  // heat.csv row every k thermal steps
    bool resumed = false;  // restarted from a checkpoint: heat.csv is written by state(), not by init
    double alpha = 0, T_ref = 0;  // thermal expansion [1/K] and its stress-free temperature [K]; alpha 0: none
    bool bond_mean = false;       // --thermal-strain bond-mean (pd::ThermalExpansion::bond_mean)
    long nsync_mk = 0;            // mechanical steps per thermal step (0: dt above)
    double source = 0;            // uniform volumetric source on the free points [W/m^3]
};

// The settings of the (checked) heat options; rho [kg/m^3], measure and heat.csv cadence as the run's.
inline HeatSettings heat_settings(const HeatOptions& h, double rho, double measure, long every)
{
    return {.model = h.heat, .integrator = h.integrator, .k = h.k, .rho_cv = rho * h.cv, .T0 = h.T0, .dt = h.dt, .hourglass = h.hourglass,
            .measure = measure, .correction = pd::parse_thermal_correction(h.correction), .every = every, .alpha = h.alpha, .T_ref = h.T_ref,
            .bond_mean = h.thermal_strain == "bond-mean", .nsync_mk = h.nsync_mk, .source = h.source};
}

// The run's temperature field (pd/heat/temperature_field.hpp: the model and integrator of the settings)
// with the heat guard and heat.csv, both run after every thermal step.
class HeatRun {
public:
    template <class Model>
    HeatRun(Model model, const HeatSettings& s, const pd::io::PointCloud& pc, const pd::Bonds& bonds, const std::filesystem::path& out,
            void (*fail)(const std::string&))
        : rho_cv_(s.rho_cv), source_(s.source), every_(s.every), volume_(pc.volume), log_path_(out / "heat.csv")
    {
        std::vector<double> T0(pc.size());
        for (std::size_t i = 0; i < pc.size(); ++i) T0[i] = std::isnan(pc.T0[i]) ? s.T0 : pc.T0[i];
        const pd::HeatIntegrator integrator = integrator_ = pd::parse_heat_integrator(s.integrator);
        auto field = pd::make_temperature_field(std::move(model), bonds, std::vector<double>(pc.size(), s.rho_cv), loads(pc, s.source), std::move(T0),
                                                integrator);
        std::printf("heat: model %s, integrator %s, held temperatures %zu\n", s.model.c_str(), s.integrator.c_str(),
                    field->conduction().loads().fixed.size());
        const double crit = crit_ = field->critical_step();
        if (s.nsync_mk > 0) {  // follow_mechanics sets dt once the mechanical step is known
        } else if (std::isnan(s.dt)) {
            if (!std::isfinite(crit)) fail("option --dt-thermal is required: no free point has a bond within --delta");
            field->dt = thermal_dt_safety * crit;
            std::printf("dt_thermal = %.17g s (%.2g x thermal critical step %.6g s)\n", field->dt, thermal_dt_safety, crit);
        } else {
            field->dt = s.dt;
            std::printf("dt_thermal = %.17g s (given; thermal critical step %.6g s, ratio %.3g)\n", s.dt, crit, s.dt / crit);
            if (s.dt > crit && integrator == pd::HeatIntegrator::explicit_euler)
                std::printf("warning: --dt-thermal exceeds the thermal critical step; explicit Euler may go unstable\n");
        }
        field_ = std::move(field);
        field_->after_step = [this](const pd::TemperatureField& f) { guard_and_log(f); };
        const auto [mn, mx] = std::minmax_element(field_->theta.begin(), field_->theta.end());
        const double width = *mx - *mn, slack = 1e-9 * std::max(std::abs(*mn), std::abs(*mx));  // round-off of a uniform field
        lo_ = *mn - guard_widening * width - slack;
        hi_ = *mx + guard_widening * width + slack;
        if (s.resumed) return;  // the complete heat.csv of the first run stays until log_state() rewrites it
        open_log();
        record();  // thermal step 0
    }

    // The thermal step of N_sync(MK) mechanical steps of dt_mech [s] (--nsync-mk).
    void follow_mechanics(long nsync, double dt_mech)
    {
        field_->dt = double(nsync) * dt_mech;
        std::printf("dt_thermal = %.17g s (N_sync(MK) = %ld mechanical steps; thermal critical step %.6g s, ratio %.3g)\n", field_->dt, nsync, crit_,
                    field_->dt / crit_);
        if (field_->dt > crit_ && integrator_ == pd::HeatIntegrator::explicit_euler)
            std::printf("warning: --nsync-mk x dt exceeds the thermal critical step; explicit Euler may go unstable\n");
    }

    pd::TemperatureField& field() { return *field_; }
    // Heat released by the mechanics (a dissipative model) raises no point by more than dT [K] above
    // what conduction allows: the guard's ceiling moves up by dT.
    void allow_rise(double dT) { rise_ += dT * (1 + 1e-9); }
    const std::vector<double>& T() const { return field_->theta; }
    long last_step = 0;  // the run's last thermal step: its heat.csv row is written whatever the cadence

    // The rows of heat.csv for a checkpoint (pd_run_checkpoint.hpp; the field's own state is the
    // scene's or the heat-only loop's): a restart writes them again, those on the cadence or at
    // last_step, so that heat.csv holds the whole run.
    void log_state(pd::StateArchive& ar)
    {
        std::vector<double> rows = ar.saving() ? rows_ : std::vector<double>{};
        ar("heat.rows", rows), ar("heat.guard_rise", rise_);
        if (ar.saving()) return;
        open_log();
        for (std::size_t q = 0; q + 5 <= rows.size(); q += 5)
            if (on_cadence(step_number(rows[q]), every_, last_step)) log_row({rows.begin() + q, rows.begin() + q + 5});
    }

private:
    std::unique_ptr<pd::TemperatureField> field_;
    pd::HeatIntegrator integrator_ = pd::HeatIntegrator::explicit_euler;
    double rho_cv_ = 0, source_ = 0, crit_ = 0, lo_ = 0, hi_ = 0;  // crit_: thermal critical step at the start [s]
    double rise_ = 0;  // the ceiling's rise by released dissipation (allow_rise) [K]
    long every_ = 1;
    std::vector<double> volume_;
    std::filesystem::path log_path_;
    std::unique_ptr<pd::io::CsvWriter> log_;
    std::vector<double> rows_;  // the rows of heat.csv (5 per row), for a checkpoint

    static pd::HeatLoads loads(const pd::io::PointCloud& pc, double source)
    {
        pd::HeatLoads l;
        if (source != 0) l.source.assign(pc.size(), source);
        for (std::size_t i = 0; i < pc.size(); ++i)
            if (!std::isnan(pc.T_fixed[i])) l.fixed.push_back(int(i)), l.fixed_value.push_back(pc.T_fixed[i]);
        return l;
    }
    // After each thermal step: the guard, and a heat.csv row every k steps and at the last one.
    void guard_and_log(const pd::TemperatureField& f)
    {
        const double shift = source_ * f.t() / rho_cv_ * (1 + 1e-9);  // a uniform source moves the band by s t/(rho cv)
        const double lo = lo_ + std::min(shift, 0.0), hi = hi_ + std::max(shift, 0.0) + rise_;
        for (std::size_t i = 0; i < f.theta.size(); ++i)
            if (!std::isfinite(f.theta[i]) || f.theta[i] < lo || f.theta[i] > hi)
                throw pd::Unstable("heat run unstable at thermal step " + std::to_string(f.step) + ", node " + std::to_string(i) +
                                       ": T = " + pd::io::format_double(f.theta[i]) + " outside the guard band [" +
                                       pd::io::format_double(lo) + ", " + pd::io::format_double(hi) + "]",
                                   f.step, int(i));
        if (f.step % every_ == 0 || f.step == last_step) record();
    }
    void record()
    {
        const std::vector<double>& T = field_->theta;
        double H = 0;  // sum rho cv V T [J, relative to T = 0 of the unit given]
        for (std::size_t i = 0; i < T.size(); ++i) H += rho_cv_ * volume_[i] * T[i];
        log_row({double(field_->step), field_->t(), H, *std::min_element(T.begin(), T.end()), *std::max_element(T.begin(), T.end())});
    }
    void open_log()
    {
        log_.reset();
        rows_.clear();
        log_ = std::make_unique<pd::io::CsvWriter>(log_path_, std::vector<std::string>{"thermal_step", "t_s", "heat_J", "T_min", "T_max"});
    }
    void log_row(const std::vector<double>& r)
    {
        log_->row({static_cast<long>(r[0]), r[1], r[2], r[3], r[4]});
        log_->flush();
        rows_.insert(rows_.end(), r.begin(), r.end());
    }
};

// Thermal expansion of the model from the run's temperatures (--alpha; none without heat or with
// alpha 0); a model that has none is refused.
template <class Model>
void attach_thermal_expansion(Model& model, const HeatSettings& s, HeatRun* heat, const std::string& name, void (*fail)(const std::string&))
{
    if (!heat || s.alpha == 0) return;
    if constexpr (requires { model.set_thermal_expansion(pd::ThermalExpansion{}); }) {
        pd::ThermalExpansion t{s.alpha, s.T_ref, &heat->T()};
        t.bond_mean = s.bond_mean;
        model.set_thermal_expansion(t);  // a refusal (std::invalid_argument) names the model: exit status 2
    } else
        fail(std::string("option --alpha: thermal expansion of ").append(name).append(" is not written"));
}

// The heat run of the settings on the given family (bonds must outlive it).
template <int D>
std::unique_ptr<HeatRun> make_heat(const HeatSettings& s, const pd::io::PointCloud& pc, const pd::Body<D>& body,
                                   const pd::Bonds& bonds, const std::filesystem::path& out, void (*fail)(const std::string&))
{
    if (s.model == "agwai")
        return std::make_unique<HeatRun>(pd::Agwai({.k = s.k, .measure = s.measure, .correction = s.correction}, body, bonds), s, pc, bonds,
                                         out, fail);
    return std::make_unique<HeatRun>(pd::CorrespondenceHeat<D>({.k = s.k, .C_hg = s.hourglass, .measure = s.measure}, body, bonds), s, pc,
                                     bonds, out, fail);
}

}  // namespace pd_run
