// pd/io/options.hpp -- command-line options of the problem drivers.
//
// A driver registers every physical and numerical parameter of its case with a default (the
// published value), a unit (SI) and a help text, then parses argv:
//
//     pd::io::Options opt("bar_modes_1d", "Fixed-free bar released from uniform strain.");
//     double& E = opt.add("E", 200e9, "Young's modulus", "Pa");
//     int& m = opt.add_int("m", 3, "horizon ratio delta/dx");
//     std::string& model = opt.add_string("model", "lps", "material model", {"pmb", "lps"});
//     pd::io::add_standard(opt, "reports/1d/bar_modes");
//     opt.require_positive("E");
//     opt.require_at_least("m", 1);
//     opt.parse(argc, argv);
//     opt.echo(std::cout);
//     opt.save_csv(opt.get_string("out") + "/params.csv");
//
// Accepted forms: `--name value`, `--name=value`, `--flag`, `--flag=true|false|1|0`, `--help`.
// A real value must be finite and 0 or of magnitude min_magnitude to max_magnitude (1e-30 to 1e30):
// no physical or numerical input of these cases comes near those bounds, and beyond them products
// the models form (E delta^4, delta^(p + D) in the horizon moments) overflow.
// `--help` prints the usage to stdout and exits 0. Every input error (unknown option, missing or
// malformed value, value outside its allowed set or range) prints ONE line
// `<program>: error: <message naming the option>` to stderr and exits with status 2 (see
// fail_input). Misuse by the programmer (unknown name in get, duplicate registration) throws
// std::logic_error instead, since it is a bug and not an input error.
//
// The references returned by add*/add_flag stay valid for the lifetime of the Options object
// and hold the parsed values after parse(). Options is neither copyable nor movable for that
// reason.
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace pd::io {

// Prints `<program>: error: <message>` (one line) to stderr and ends the process with status 2.
// Used by drivers and the library for every invalid user input.
[[noreturn]] void fail_input(const std::string& program, const std::string& message);

class Options {
public:
    static constexpr double min_magnitude = 1e-30, max_magnitude = 1e30;  // of a nonzero real value
    // Empty when v is 0 or within the magnitude range, else what is wrong (for the message).
    static std::string magnitude_error(double v)
    {
        return v == 0 || (std::abs(v) >= min_magnitude && std::abs(v) <= max_magnitude) ? "" : "must be 0 or of magnitude 1e-30 to 1e30";
    }

    Options(std::string program, std::string description);
    Options(const Options&) = delete;
    Options& operator=(const Options&) = delete;
    ~Options();

    // Registration. `name` is given without the leading dashes ("E", "dt-factor").
    // The returned reference holds the default until parse() and the parsed value after it.
    double& add(const std::string& name, double def, const std::string& help,
                const std::string& unit = "");
    int& add_int(const std::string& name, int def, const std::string& help,
                 const std::string& unit = "");
    // allowed: if not empty, the value must be one of these (the default too).
    std::string& add_string(const std::string& name, const std::string& def,
                            const std::string& help, std::vector<std::string> allowed = {});
    // A flag is false unless given on the command line.
    bool& add_flag(const std::string& name, const std::string& help);

    // Parses argv[1..argc-1]; argv[0] is ignored (messages use the program name given to the
    // constructor). Runs the pending require_* checks afterwards. Exits 0 on --help and 2 on
    // any input error.
    void parse(int argc, const char* const* argv);

    // Validation of numeric (double or int) options; a violation ends with fail_input naming the
    // option. Called before parse(), the check is recorded and runs at the end of parse();
    // called after parse(), it runs at once. A NaN value can only be a driver's default (the
    // command line rejects non-finite numbers); it stands for "automatic" and passes the checks.
    void require_positive(const std::string& name);                      // value > 0
    void require_at_least(const std::string& name, double v);            // value >= v
    void require_range(const std::string& name, double lo, double hi,    // lo <(=) value <(=) hi
                       bool lo_inclusive = true, bool hi_inclusive = true);

    // Values by name (after parse: the parsed value, before: the default).
    // get() accepts double and int options.
    double get(const std::string& name) const;
    int get_int(const std::string& name) const;
    std::string get_string(const std::string& name) const;
    bool get_flag(const std::string& name) const;
    bool has(const std::string& name) const;            // registered?
    bool given(const std::string& name) const;          // set on the command line?
    // A default that depends on other options (--quick's coarse case): replaces the value of a
    // real, integer or string option that was NOT given on the command line; a given value stays.
    // Called between parse() and echo()/save_csv(), so that params.csv records the value used.
    void set_default(const std::string& name, double value);
    void set_default(const std::string& name, const std::string& value);

    // One line per option, in registration order: `  name = value [unit]` (no brackets when the
    // option has no unit). Doubles are written in the shortest form that reads back exactly.
    void echo(std::ostream& os) const;
    // An option that does not change a run's results and is left out of echo() and save_csv().
    void not_recorded(const std::string& name);
    // Writes the same content as CSV with header `option,value,unit`; creates parent folders.
    // Throws std::runtime_error if the file cannot be written.
    void save_csv(const std::filesystem::path& path) const;
    // The --help text.
    void print_usage(std::ostream& os) const;

    // fail_input(program(), message): for checks a driver makes itself.
    [[noreturn]] void fail(const std::string& message) const;

    const std::string& program() const { return program_; }
    const std::string& description() const { return description_; }

private:
    struct Entry;
    Entry& lookup(const std::string& name) const;       // throws std::logic_error if unknown
    Entry* find(const std::string& name) const;         // nullptr if unknown
    Entry& insert(const std::string& name, const std::string& help, const std::string& unit);
    void set_value(Entry& e, const std::string& text);  // fail_input on a malformed value
    double numeric(const std::string& name) const;      // fail-free read of a double/int option
    void check_or_defer(std::function<void()> check);

    std::string program_;
    std::string description_;
    std::vector<std::unique_ptr<Entry>> entries_;       // unique_ptr: stable addresses
    std::vector<std::function<void()>> checks_;         // deferred require_* checks
    bool parsed_ = false;
};

// The options every driver accepts (DESIGN.md, "Problem drivers"):
//   --quick (flag: coarse, seconds), --check (flag: exit non-zero when the tolerance is missed),
//   --out DIR (string, default default_out), --threads N (int, 0 = OpenMP default; must be >= 0),
//   --max-steps N (int, default 1e8, 0 = none: the step limit of core/errors.hpp, require_steps).
// out_help is the help text of --out; a driver that writes more than CSV files (e.g. VTU) says so there.
void add_standard(Options& opt, const std::string& default_out,
                  const std::string& out_help = "output folder (CSV files and params.csv)");

}  // namespace pd::io
