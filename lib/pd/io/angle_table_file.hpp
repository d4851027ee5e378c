// pd/io/angle_table_file.hpp -- an axisymmetric surface load (bc/angle_table.hpp) from a CSV file:
// the column `angle_deg` and the named value column. std::runtime_error names the file.
#pragma once
#include "pd/bc/angle_table.hpp"
#include "pd/io/csv.hpp"

#include <filesystem>
#include <stdexcept>
#include <string>

namespace pd {

inline AngleTable read_angle_table(const std::filesystem::path& path, const std::string& column)
{
    const io::CsvTable t = io::read_csv(path);
    try {
        return AngleTable(t.numbers("angle_deg"), t.numbers(column));
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(path.string() + ": " + e.what());
    }
}

}  // namespace pd
