// tools/csv_records.hpp -- what the report tools (ledger, report_index) read: a CSV as records
// (column name -> field, in file order) and a whole file as text.
#pragma once
#include "pd/io/csv.hpp"

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace tools {

using Record = std::map<std::string, std::string>;

// Throws std::invalid_argument naming a missing file (the tools' exit status 2).
inline std::vector<Record> records(const std::filesystem::path& path)
{
    if (!std::filesystem::exists(path)) throw std::invalid_argument("no file " + path.string());
    const pd::io::CsvTable t = pd::io::read_csv(path);
    std::vector<Record> out;
    for (const pd::io::CsvRow& r : t.rows) {
        Record rec;
        for (std::size_t c = 0; c < t.header.size(); ++c) rec[t.header[c]] = r.fields[c];
        out.push_back(rec);
    }
    return out;
}

inline std::string slurp(const std::filesystem::path& p)
{
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace tools
