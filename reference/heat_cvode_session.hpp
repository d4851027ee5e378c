// reference/heat_cvode_session.hpp -- the CVODE session of the method-of-lines heat references
// (heat_prism.cpp, heat_kirchhoff.cpp): SUNDIALS context, state y (every unknown at T0), the
// interpolation vector dky, an SPGMR linear solver and a BDF integrator, freed in reverse order on
// every exit (normal or exception); and the crossing time of a probe on CVODE's interpolant over
// the last step, by bisection of [lo, hi] down to a width tol [s].
#pragma once
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace pd::ref {

class HeatCvodeSession {
public:
    SUNContext ctx = nullptr;
    N_Vector y = nullptr, dky = nullptr;
    SUNLinearSolver LS = nullptr;
    void* mem = nullptr;

    // n unknowns at T0 [K or C]; SPGMR with preconditioning prec (SUN_PREC_NONE, SUN_PREC_LEFT) and
    // Krylov dimension krylov; who: the reference's name in error messages.
    HeatCvodeSession(sunindextype n, double T0, int prec, int krylov, const char* who) : who_(who)
    {
        ok(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
        y = N_VNew_Serial(n, ctx), dky = N_VNew_Serial(n, ctx);
        std::fill(N_VGetArrayPointer(y), N_VGetArrayPointer(y) + n, T0);
        LS = SUNLinSol_SPGMR(y, prec, krylov, ctx);
        mem = CVodeCreate(CV_BDF, ctx);
    }
    ~HeatCvodeSession() { CVodeFree(&mem), SUNLinSolFree(LS), N_VDestroy(y), N_VDestroy(dky), SUNContext_Free(&ctx); }
    HeatCvodeSession(const HeatCvodeSession&) = delete;
    HeatCvodeSession& operator=(const HeatCvodeSession&) = delete;

    // Throws std::runtime_error naming the reference and the call when a SUNDIALS flag is negative.
    void ok(int flag, const char* what) const
    {
        if (flag < 0) throw std::runtime_error(std::string(who_) + ": " + what + " failed, flag " + std::to_string(flag));
    }

    // Time in [lo, hi] [s] at which short(T) (the probe of the interpolated state T has not reached
    // its target) turns false: bisection while hi - lo > tol [s].
    template <class Short>
    double crossing(double lo, double hi, double tol, Short&& short_of_target) const
    {
        while (hi - lo > tol) {
            const double mid = 0.5 * (lo + hi);
            ok(CVodeGetDky(mem, mid, 0, dky), "CVodeGetDky");
            (short_of_target(N_VGetArrayPointer(dky)) ? lo : hi) = mid;
        }
        return 0.5 * (lo + hi);
    }

private:
    const char* who_;
};

}  // namespace pd::ref
