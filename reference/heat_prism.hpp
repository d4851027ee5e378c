// reference/heat_prism.hpp -- classical 3D transient conduction in a rectangular prism, by the
// finite-difference method of lines integrated with SUNDIALS CVODE (BDF, matrix-free GMRES).
// Independent of the peridynamics library. spec/000b sec. 5.8 (T8) and V9.
//
// Problem: rho c T_t = k lap T in [0, Lx] x [0, Ly] x [0, Lz]; T = T_end on the faces x = 0 and
// x = Lx from t = 0; the four lateral faces adiabatic; T(x, 0) = T0.
// Discretisation: cell-centred grid of nx x ny x nz cells; 7-point Laplacian; Dirichlet faces by
// the ghost value 2 T_end - T_cell (second order), adiabatic faces by mirror ghosts. The lateral
// faces being adiabatic and the data uniform across, the solution does not depend on y and z: this
// reference checks the 3D machinery of the comparison, its value tends to the 1D continuum one.
// Time of a probe (mean of the 8 cells around the centre, or 4/2/1 when counts are odd) reaching
// T_target: CVODE one step at a time, crossing located on CVODE's interpolant by bisection.
#pragma once

namespace pd::ref {

struct HeatPrism {
    double Lx = 0.1, Ly = 0.01, Lz = 0.01;  // [m] (x: the axis whose end faces are held)
    int nx = 100, ny = 10, nz = 10;          // cells
    double alpha = 0;                        // diffusivity k/(rho c) [m^2/s]
    double T0 = 0, T_end = 100;              // [C or K]
};

struct PrismCrossing {
    double t = 0;      // time at which the centre reaches the target [s]
    long steps = 0;    // CVODE internal steps
};

// Throws std::invalid_argument for bad sizes or a target outside (T0, T_end), std::runtime_error
// when CVODE fails or the target is not reached by t_max [s].
PrismCrossing heat_prism_time_to(const HeatPrism& p, double T_target, double rtol = 1e-9, double t_max = 1e5);

}  // namespace pd::ref
