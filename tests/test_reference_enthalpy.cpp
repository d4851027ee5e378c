// reference/enthalpy: the exact enthalpy of the EN 1993-1-2 carbon-steel specific heat against the
// numbers printed in the spec (spec/000a sec. 3.9 eq. 3.37 and the V2 checkpoint table).
#include "reference/enthalpy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace {

// Spec/000a V2 checkpoints, q(theta) [J/kg], printed to 0.01 J/kg.
constexpr double table_theta[] = {100, 200, 300, 400, 500, 600, 700, 730, 735, 740, 800, 900, 1000, 1100, 1200};
constexpr double table_q[] = {37206.98,  88191.15,  142920.32, 201344.48, 264745.65, 335737.82, 419106.08, 459345.07,
                              475427.81, 492603.59, 561600.83, 632063.84, 697063.84, 762063.84, 827063.84};

}  // namespace

TEST(ReferenceEnthalpy, TotalTo1200IsTheSourceValue)
{
    // Seed 000a eq. 3.37: 827063.84 J/kg; printed to 0.01 J/kg, so 0.005 J/kg + rounding.
    EXPECT_NEAR(pd::ref::carbon_steel_enthalpy(1200), 827063.84, 0.006);
    EXPECT_EQ(pd::ref::carbon_steel_enthalpy(20), 0.0);
}

TEST(ReferenceEnthalpy, SpecCheckpointTable)
{
    for (std::size_t k = 0; k < std::size(table_theta); ++k)
        EXPECT_NEAR(pd::ref::carbon_steel_enthalpy(table_theta[k]), table_q[k], 0.006) << "theta = " << table_theta[k];
}

TEST(ReferenceEnthalpy, PrintedCoefficientGivesTheErratumTotal)
{
    // Erratum E14: with the printed 7.33e-1 the total is 819871.84 J/kg, i.e. 1200 C reached 7192 s
    // early at rho = 1, s = 1.
    const pd::ref::CarbonSteelCp printed{7.33e-1};
    EXPECT_NEAR(pd::ref::carbon_steel_enthalpy(1200, printed), 819871.84, 0.006);
    EXPECT_NEAR(pd::ref::adiabatic_heating_time(1, 1, 20, 1200) - pd::ref::adiabatic_heating_time(1, 1, 20, 1200, printed),
                7192.0, 0.006);
}

TEST(ReferenceEnthalpy, SpecificHeatValues)
{
    // Spec/000a V2, printed to 0.01 J/(kg K) (c(20) = 425 + 15.46 - 0.676 + 0.01776 = 439.80176).
    EXPECT_NEAR(pd::ref::carbon_steel_specific_heat(20), 439.80176, 1e-9);
    EXPECT_NEAR(pd::ref::carbon_steel_specific_heat(600), 760.22, 0.005);
    EXPECT_NEAR(pd::ref::carbon_steel_specific_heat(735), 5000.0, 1e-9);
    EXPECT_NEAR(pd::ref::carbon_steel_specific_heat(740), 2525.0, 1e-9);
    EXPECT_EQ(pd::ref::carbon_steel_specific_heat(1000), 650.0);
    EXPECT_THROW(pd::ref::carbon_steel_specific_heat(19.9), std::invalid_argument);
    EXPECT_THROW(pd::ref::carbon_steel_enthalpy(1200.1), std::invalid_argument);
}

TEST(ReferenceEnthalpy, EnthalpyIsTheIntegralOfTheSpecificHeat)
{
    // Central difference of q against c inside each branch (h = 1e-3 C; q''' h^2/6 below 1e-4).
    for (double T : {50.0, 450.0, 650.0, 733.0, 736.0, 850.0, 1000.0}) {
        const double h = 1e-3;
        const double dq = (pd::ref::carbon_steel_enthalpy(T + h) - pd::ref::carbon_steel_enthalpy(T - h)) / (2 * h);
        EXPECT_NEAR(dq, pd::ref::carbon_steel_specific_heat(T), 1e-4 * pd::ref::carbon_steel_specific_heat(T)) << T;
    }
}

TEST(ReferenceEnthalpy, InverseAndHeatingTime)
{
    for (std::size_t k = 0; k < std::size(table_theta); ++k)
        EXPECT_NEAR(pd::ref::carbon_steel_temperature_at_enthalpy(pd::ref::carbon_steel_enthalpy(table_theta[k])),
                    table_theta[k], 1e-9 * table_theta[k]);
    // t = rho (q(theta) - q(theta0)) / s: rho = 7850, s = 1e6 W/m^3, 20 -> 1200 C; the printed q is
    // rounded to 0.01 J/kg, hence 7850/1e6 x 0.006 s.
    EXPECT_NEAR(pd::ref::adiabatic_heating_time(7850, 1e6, 20, 1200), 7850 * 827063.84 / 1e6, 7850 / 1e6 * 0.006);
    EXPECT_NEAR(pd::ref::adiabatic_heating_time(1, 1, 735, 1200), 827063.84 - 475427.81, 0.011);
    EXPECT_THROW(pd::ref::carbon_steel_temperature_at_enthalpy(-1), std::invalid_argument);
}
