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

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <type_traits>
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
    // Throws std::invalid_argument naming the checkpoint file and `what`.
    [[noreturn]] void fail(const std::string& what) const;

    // Visits one entry: saving stores the value, loading restores it.
    void operator()(const std::string& name, std::vector<double>& v);
    void operator()(const std::string& name, std::vector<std::uint8_t>& v);
    void operator()(const std::string& name, double& x);
    void operator()(const std::string& name, long& x);
    void operator()(const std::string& name, std::string& s);
    void operator()(const std::string& name, int& x)
    {
        long v = x;
        (*this)(name, v);
        x = static_cast<int>(v);
    }
    void operator()(const std::string& name, bool& x)
    {
        long v = x;
        (*this)(name, v);
        x = v != 0;
    }
    template <int D>
    void operator()(const std::string& name, Field<D>& f)
    {
        for (int d = 0; d < D; ++d) (*this)(name + "." + "xyz"[d], f.c[d]);
    }
    template <int D>
    void operator()(const std::string& name, Vec<D>& x)
    {
        std::vector<double> v(x.c.begin(), x.c.end());
        (*this)(name, v);
        for (int d = 0; d < D; ++d) x[d] = v[d];  // loading checked the length (D values)
    }
    template <int D>
    void operator()(const std::string& name, std::vector<Vec<D>>& xs)  // stored as D arrays
    {
        Field<D> f(xs.size());
        for (std::size_t i = 0; i < xs.size(); ++i) f.set(i, xs[i]);
        if (!saving()) f = Field<D>();  // loading: any length
        (*this)(name, f);
        for (int d = 1; d < D; ++d)
            if (f.c[d].size() != f.size()) fail("entry '" + name + "' is cut");
        xs.resize(f.size());
        for (std::size_t i = 0; i < xs.size(); ++i) xs[i] = f[i];
    }

    // A vector of fixed-size blocks of doubles (e.g. Eigen's fixed-size matrices), stored flat.
    template <class M>
    void blocks(const std::string& name, std::vector<M>& v)
    {
        static_assert(sizeof(M) % sizeof(double) == 0, "blocks of doubles only");
        constexpr std::size_t n = sizeof(M) / sizeof(double);
        std::vector<double> flat;
        if (saving()) {
            flat.resize(v.size() * n);
            for (std::size_t i = 0; i < v.size(); ++i) std::copy(v[i].data(), v[i].data() + n, flat.begin() + i * n);
        }
        (*this)(name, flat);
        if (saving()) return;
        if (flat.size() % n != 0) fail("entry '" + name + "' is cut");
        if (!v.empty() && v.size() != flat.size() / n)
            fail("entry '" + name + "' has " + std::to_string(flat.size() / n) + " blocks, the run has " + std::to_string(v.size()) +
                 " (a checkpoint of another scene)");
        v.resize(flat.size() / n);
        for (std::size_t i = 0; i < v.size(); ++i) std::copy(flat.begin() + i * n, flat.begin() + (i + 1) * n, v[i].data());
    }

    // A vector of plain records (trivially copyable structs of numbers), stored as their bytes.
    template <class T>
        requires std::is_trivially_copyable_v<T>
    void records(const std::string& name, std::vector<T>& v)
    {
        std::vector<std::uint8_t> bytes;
        if (saving()) {
            bytes.resize(v.size() * sizeof(T));
            if (!v.empty()) std::memcpy(bytes.data(), v.data(), bytes.size());
        }
        (*this)(name, bytes);
        if (saving()) return;
        if (bytes.size() % sizeof(T) != 0) fail("entry '" + name + "' is cut");
        v.resize(bytes.size() / sizeof(T));
        if (!v.empty()) std::memcpy(v.data(), bytes.data(), bytes.size());
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
    void put(const std::string& name, Entry entry);  // saving; a name saved twice is a logic_error
};

}  // namespace pd
