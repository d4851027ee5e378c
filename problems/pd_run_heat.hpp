// problems/pd_run_heat.hpp -- the heat-conduction part of pd_run (issue 4): its options, their
// checks, and HeatRun, the temperature field of a point cloud advanced step by step.
//   rho cv dT_i/dt = Q_i(T) on free nodes, T_i = T_fixed_i on held nodes (pd/heat/conduction.hpp),
//   Q from Agwai's bond-based model or the correspondence heat model (pd/heat/agwai.hpp,
//   correspondence_heat.hpp); no sources, no convection, no coupling to the mechanics (yet).
// Integrators: explicit Euler, implicit Euler, CVODE BDF (one advance() per thermal step).
// dt_thermal default = 0.5 x the Gershgorin thermal critical step (spec/000b eq. 3.20).
// Heat guard: with no sources the exact temperatures stay in the range of the initial and held
// values (maximum principle); a temperature outside that range widened by 10 x its width, or a
// non-finite one, throws pd::Unstable naming the thermal step and the node.
// Writes heat.csv: thermal_step,t_s,heat_J (sum rho cv V T),T_min,T_max.
#pragma once
#include "pd_run_checkpoint.hpp"
#include "pd/heat/agwai.hpp"
#include "pd/heat/conduction.hpp"
#include "pd/heat/correspondence_heat.hpp"
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
            opt.add_string("thermal-correction", "none", "Agwai thermal correction factor", {"none", "per-node", "pair-mean"})};
}

// Cross-checks of the heat options; `mechanics` = the mechanical run is on. fail() never returns.
template <class Fail>
void check_heat_options(const pd::io::Options& opt, const HeatOptions& h, bool mechanics, Fail fail)
{
    const bool on = h.heat != "none";
    for (const char* name : {"k", "cv", "T0", "dt-thermal", "thermal-steps", "thermal-integrator", "heat-hourglass",
                             "thermal-correction"})
        if (opt.given(name) && !on) fail(std::string("option --") + name + " needs --heat agwai|correspondence");
    if (!on) return;
    for (const char* name : {"k", "cv"})
        if (!opt.given(name)) fail(std::string("option --") + name + " is required with --heat");
    if (mechanics && opt.given("thermal-steps"))
        fail("option --thermal-steps applies to --mechanics off (with mechanics the heat follows the mechanical clock)");
    if (opt.given("heat-hourglass") && h.heat != "correspondence") fail("option --heat-hourglass applies to --heat correspondence only");
    if (opt.given("thermal-correction") && h.heat != "agwai") fail("option --thermal-correction applies to --heat agwai only");
    if (h.hourglass < 0) fail("option --heat-hourglass must be >= 0, got " + pd::io::format_double(h.hourglass));
}

struct HeatSettings {
    std::string model, integrator;
    double k = 0, rho_cv = 0, T0 = 0, dt = 0, hourglass = 0, measure = 1;  // [W/(m K)], [J/(m^3 K)], [K], [s], [-], [m^(3-D)]
    pd::ThermalCorrection correction = pd::ThermalCorrection::none;
    long every = 1;  // heat.csv row every k thermal steps
    bool resumed = false;  // restarted from a checkpoint: heat.csv is written by state(), not by init
};

// The temperature field and its integrator, whatever the heat model (type-erased for the driver).
class HeatRun {
public:
    virtual ~HeatRun() = default;
    std::vector<double> T;  // [K or C]
    long step = 0;          // thermal steps taken
    double dt = 0;          // [s]
    double t() const { return double(step) * dt; }
    const std::vector<double>& heat_flow() { return flow(T); }  // Q at the current T [W/m^3]

    // One thermal step, the guard, and a heat.csv row every k steps (and when `last`).
    void advance(bool last)
    {
        take_step();
        ++step;
        for (std::size_t i = 0; i < T.size(); ++i)
            if (!std::isfinite(T[i]) || T[i] < lo_ || T[i] > hi_)
                throw pd::Unstable("heat run unstable at thermal step " + std::to_string(step) + ", node " + std::to_string(i) +
                                       ": T = " + pd::io::format_double(T[i]) + " outside the guard band [" +
                                       pd::io::format_double(lo_) + ", " + pd::io::format_double(hi_) + "]",
                                   step, int(i));
        if (step % every_ == 0 || last) record();
    }
    void record()
    {
        double H = 0;  // sum rho cv V T [J, relative to T = 0 of the unit given]
        for (std::size_t i = 0; i < T.size(); ++i) H += rho_cv_ * volume_[i] * T[i];
        log_row({double(step), t(), H, *std::min_element(T.begin(), T.end()), *std::max_element(T.begin(), T.end())});
    }
    // Its part of a checkpoint (pd_run_checkpoint.hpp): the field, the step and the rows of heat.csv
    // (a restart writes them again, those on the cadence or at last_step, so that heat.csv holds the
    // whole run).
    void state(pd::StateArchive& ar, long last_step)
    {
        ar("heat.T", T), ar("heat.step", step);
        std::vector<double> rows = ar.saving() ? rows_ : std::vector<double>{};
        ar("heat.rows", rows);
        if (ar.saving()) return;
        open_log();
        for (std::size_t q = 0; q + 5 <= rows.size(); q += 5)
            if (on_cadence(step_number(rows[q]), every_, last_step)) log_row({rows.begin() + q, rows.begin() + q + 5});
    }

protected:
    virtual void take_step() = 0;
    virtual const std::vector<double>& flow(const std::vector<double>& T) = 0;
    void init(const HeatSettings& s, const pd::io::PointCloud& pc, const std::filesystem::path& out)
    {
        rho_cv_ = s.rho_cv;
        every_ = s.every;
        volume_ = pc.volume;
        const auto [mn, mx] = std::minmax_element(T.begin(), T.end());
        const double width = *mx - *mn, slack = 1e-9 * std::max(std::abs(*mn), std::abs(*mx));  // round-off of a uniform field
        lo_ = *mn - guard_widening * width - slack;
        hi_ = *mx + guard_widening * width + slack;
        log_path_ = out / "heat.csv";
        if (s.resumed) return;  // the complete heat.csv of the first run stays until state() rewrites it
        open_log();
        record();  // thermal step 0
    }

private:
    double rho_cv_ = 0, lo_ = 0, hi_ = 0;
    long every_ = 1;
    std::vector<double> volume_;
    std::filesystem::path log_path_;
    std::unique_ptr<pd::io::CsvWriter> log_;
    std::vector<double> rows_;  // the rows of heat.csv (5 per row), for a checkpoint

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

template <class Model>
class HeatRunOf : public HeatRun {
public:
    HeatRunOf(Model model, const HeatSettings& s, const pd::io::PointCloud& pc, const pd::Bonds& bonds,
              const std::filesystem::path& out, void (*fail)(const std::string&))
        : model_(std::move(model)), bonds_(bonds), integrator_(s.integrator),
          cond_(model_, bonds, std::vector<double>(pc.size(), s.rho_cv), loads(pc))
    {
        T.resize(pc.size());
        for (std::size_t i = 0; i < pc.size(); ++i) T[i] = std::isnan(pc.T0[i]) ? s.T0 : pc.T0[i];
        cond_.apply_fixed(T);  // a held node starts at its held temperature
        std::printf("heat: model %s, integrator %s, held temperatures %zu\n", s.model.c_str(), s.integrator.c_str(),
                    cond_.loads().fixed.size());
        const double crit = pd::thermal_critical_step(model_, bonds, cond_, T);
        if (std::isnan(s.dt)) {
            if (!std::isfinite(crit)) fail("option --dt-thermal is required: no free point has a bond within --delta");
            dt = thermal_dt_safety * crit;
            std::printf("dt_thermal = %.17g s (%.2g x thermal critical step %.6g s)\n", dt, thermal_dt_safety, crit);
        } else {
            dt = s.dt;
            std::printf("dt_thermal = %.17g s (given; thermal critical step %.6g s, ratio %.3g)\n", dt, crit, dt / crit);
            if (dt > crit && integrator_ == "explicit")
                std::printf("warning: --dt-thermal exceeds the thermal critical step; explicit Euler may go unstable\n");
        }
        init(s, pc, out);
        if (integrator_ == "cvode") cvode_ = std::make_unique<pd::HeatCvode<Model>>(cond_, model_, bonds, T, 0.0);
    }

private:
    static pd::HeatLoads loads(const pd::io::PointCloud& pc)
    {
        pd::HeatLoads l;
        for (std::size_t i = 0; i < pc.size(); ++i)
            if (!std::isnan(pc.T_fixed[i])) l.fixed.push_back(int(i)), l.fixed_value.push_back(pc.T_fixed[i]);
        return l;
    }
    void take_step() override
    {
        if (integrator_ == "explicit") cond_.explicit_euler(T, dt);
        else if (integrator_ == "implicit") cond_.implicit_euler(T, dt);
        else T = cvode_->advance(double(step + 1) * dt);
    }
    const std::vector<double>& flow(const std::vector<double>& theta) override
    {
        pd::heat_flow(model_, bonds_, theta, Q_);
        return Q_;
    }

    Model model_;
    const pd::Bonds& bonds_;
    std::string integrator_;
    pd::Conduction<Model> cond_;
    std::unique_ptr<pd::HeatCvode<Model>> cvode_;
    std::vector<double> Q_;
};

// The heat run of the settings on the given family (bonds must outlive it).
template <int D>
std::unique_ptr<HeatRun> make_heat(const HeatSettings& s, const pd::io::PointCloud& pc, const pd::Body<D>& body,
                                   const pd::Bonds& bonds, const std::filesystem::path& out, void (*fail)(const std::string&))
{
    if (s.model == "agwai")
        return std::make_unique<HeatRunOf<pd::Agwai>>(
            pd::Agwai({.k = s.k, .measure = s.measure, .correction = s.correction}, body, bonds), s, pc, bonds, out, fail);
    return std::make_unique<HeatRunOf<pd::CorrespondenceHeat<D>>>(
        pd::CorrespondenceHeat<D>({.k = s.k, .C_hg = s.hourglass, .measure = s.measure}, body, bonds), s, pc, bonds, out, fail);
}

}  // namespace pd_run
