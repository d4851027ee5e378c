// pd/core/state_archive.hpp -- a run's state as named arrays: the checkpoint of a restartable run.
//
// Every stateful part of a run (integrator, bonds, model history, damage rule, heat field) writes
// ONE function that visits its state, used in both directions:
//
//     void state(StateArchive& ar) { ar("u", u); ar("t", t); ar("intact", intact); }
//
// A saving archive copies the values in; a loading archive copies them back out, bit for bit, and
// refuses an entry that is missing or whose length differs from a non-empty target (the checkpoint
// of another scene). The file (write/read) is binary: a magic line, then per entry its name, type,
// length and raw bytes, then an end marker; it is written as <file>.part and renamed when complete,
// so that a run killed while writing leaves the previous checkpoint intact. Values are stored in the
// machine's own byte order: a checkpoint is read back on the machine type that wrote it.
// Errors (unreadable, cut or foreign file; missing or mismatched entry) throw std::invalid_argument
// naming the file and the entry (exit status 2 in a driver).
#pragma once
#include "pd/core/field.hpp"

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace pd {

class StateArchive {
public:
    enum class Mode { save, load };

    StateArchive() = default;  // an empty archive for saving
    // Reads a checkpoint file for loading (throws std::invalid_argument naming the file).
    static StateArchive read(const std::filesystem::path& path);
    // Writes the archive to path atomically (path.part, then rename); throws std::runtime_error.
    void write(const std::filesystem::path& path) const;

    bool saving() const { return mode_ == Mode::save; }

    // Visits one entry: saving stores the value, loading restores it.
    void operator()(const std::string& name, std::vector<double>& v);
    void operator()(const std::string& name, std::vector<std::uint8_t>& v);
    void operator()(const std::string& name, double& x);
    void operator()(const std::string& name, long& x);
    void operator()(const std::string& name, std::string& s);
    template <int D>
    void operator()(const std::string& name, Field<D>& f)
    {
        for (int d = 0; d < D; ++d) (*this)(name + "." + "xyz"[d], f.c[d]);
    }

private:
    enum class Type : std::uint8_t { real = 1, byte = 2, integer = 3, text = 4 };
    struct Entry {
        Type type;
        std::string bytes;
    };
    Mode mode_ = Mode::save;
    std::filesystem::path path_;  // the file read (for messages)
    std::map<std::string, Entry> entries_;

    const Entry& find(const std::string& name, Type type) const;
    [[noreturn]] void fail(const std::string& what) const;
};

}  // namespace pd
