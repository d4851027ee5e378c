// pd/io/options.cpp -- command-line parsing, validation, echo and params.csv of pd::io::Options.
// See options.hpp for the accepted syntax and the error contract (one line, exit status 2).
#include "pd/io/options.hpp"

#include "pd/io/csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <stdexcept>

namespace pd::io {

namespace {

enum class Kind { Real, Int, String, Flag };

bool starts_with_dashes(const char* s) { return s[0] == '-' && s[1] == '-'; }

std::string join(const std::vector<std::string>& v, const char* sep)
{
    std::string s;
    for (std::size_t k = 0; k < v.size(); ++k) s += (k ? sep : "") + v[k];
    return s;
}

}  // namespace

struct Options::Entry {
    std::string name, help, unit;
    Kind kind = Kind::Real;
    double real = 0.0;
    int integer = 0;
    std::string text;
    bool flag = false;
    std::vector<std::string> allowed;  // String only; empty = any text
    std::string default_text;          // for --help
    bool given = false;
    bool recorded = true;              // written by echo() and save_csv()

    std::string value_text() const
    {
        switch (kind) {
        case Kind::Real: return format_shortest(real);
        case Kind::Int: return std::to_string(integer);
        case Kind::String: return text;
        case Kind::Flag: return flag ? "true" : "false";
        }
        return {};
    }
    std::string placeholder() const
    {
        switch (kind) {
        case Kind::Real: return " X";
        case Kind::Int: return " N";
        case Kind::String: return allowed.empty() ? " TEXT" : " {" + join(allowed, ",") + "}";
        case Kind::Flag: return "";
        }
        return {};
    }
};

void fail_input(const std::string& program, const std::string& message)
{
    std::string line = message;
    std::replace(line.begin(), line.end(), '\n', ' ');  // the contract is one line
    std::cout.flush();
    std::cerr << program << ": error: " << line << std::endl;
    std::exit(2);
}

Options::Options(std::string program, std::string description)
    : program_(std::move(program)), description_(std::move(description))
{
}

Options::~Options() = default;

Options::Entry* Options::find(const std::string& name) const
{
    for (const auto& e : entries_)
        if (e->name == name) return e.get();
    return nullptr;
}

Options::Entry& Options::lookup(const std::string& name) const
{
    Entry* e = find(name);
    if (!e) throw std::logic_error(program_ + ": no option named '" + name + "' is registered");
    return *e;
}

Options::Entry& Options::insert(const std::string& name, const std::string& help, const std::string& unit)
{
    if (name.empty() || name[0] == '-' || name.find_first_of("= \t") != std::string::npos ||
        name == "help")
        throw std::logic_error(program_ + ": invalid option name '" + name + "'");
    if (find(name)) throw std::logic_error(program_ + ": option '" + name + "' registered twice");
    entries_.push_back(std::make_unique<Entry>());
    Entry& e = *entries_.back();
    e.name = name;
    e.help = help;
    e.unit = unit;
    return e;
}

double& Options::add(const std::string& name, double def, const std::string& help, const std::string& unit)
{
    Entry& e = insert(name, help, unit);
    e.kind = Kind::Real;
    e.real = def;
    e.default_text = format_shortest(def);
    return e.real;
}

int& Options::add_int(const std::string& name, int def, const std::string& help, const std::string& unit)
{
    Entry& e = insert(name, help, unit);
    e.kind = Kind::Int;
    e.integer = def;
    e.default_text = std::to_string(def);
    return e.integer;
}

std::string& Options::add_string(const std::string& name, const std::string& def, const std::string& help,
                                 std::vector<std::string> allowed)
{
    if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), def) == allowed.end())
        throw std::logic_error(program_ + ": default '" + def + "' of option '" + name + "' is not allowed");
    Entry& e = insert(name, help, "");
    e.kind = Kind::String;
    e.text = def;
    e.allowed = std::move(allowed);
    e.default_text = def.empty() ? "\"\"" : def;
    return e.text;
}

bool& Options::add_flag(const std::string& name, const std::string& help)
{
    Entry& e = insert(name, help, "");
    e.kind = Kind::Flag;
    e.flag = false;
    return e.flag;
}

void Options::set_value(Entry& e, const std::string& text)
{
    const std::string opt = "option --" + e.name;
    switch (e.kind) {
    case Kind::Real: {
        double v = 0.0;
        if (!parse_double(text, v)) fail(opt + " expects a number, got '" + text + "'");
        if (!std::isfinite(v)) fail(opt + " expects a finite number, got '" + text + "'");
        if (const std::string bad = magnitude_error(v); !bad.empty()) fail(opt + " " + bad + ", got '" + text + "'");
        e.real = v;
        break;
    }
    case Kind::Int: {
        const char* b = text.c_str() + (text.size() > 1 && text[0] == '+' ? 1 : 0);
        const char* end = text.c_str() + text.size();
        int v = 0;
        const auto res = std::from_chars(b, end, v);
        if (res.ec == std::errc::result_out_of_range) fail(opt + " value '" + text + "' is out of the int range");
        if (res.ec != std::errc() || res.ptr != end || text.empty())
            fail(opt + " expects an integer, got '" + text + "'");
        e.integer = v;
        break;
    }
    case Kind::String:
        if (!e.allowed.empty() && std::find(e.allowed.begin(), e.allowed.end(), text) == e.allowed.end())
            fail(opt + " must be one of " + join(e.allowed, "|") + ", got '" + text + "'");
        e.text = text;
        break;
    case Kind::Flag:
        if (text == "true" || text == "1" || text == "yes" || text == "on") e.flag = true;
        else if (text == "false" || text == "0" || text == "no" || text == "off") e.flag = false;
        else fail(opt + " is a flag (true|false), got '" + text + "'");
        break;
    }
}

void Options::parse(int argc, const char* const* argv)
{
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            print_usage(std::cout);
            std::exit(0);
        }
    }
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.size() < 3 || !starts_with_dashes(argv[i]))
            fail("unexpected argument '" + arg + "' (options are --name value; see --help)");
        const std::string body = arg.substr(2);
        const auto eq = body.find('=');
        const std::string name = body.substr(0, eq);
        Entry* e = find(name);
        if (!e) fail("unknown option --" + name + " (see --help)");
        std::string value;
        if (eq != std::string::npos) value = body.substr(eq + 1);
        else if (e->kind == Kind::Flag) value = "true";
        else if (i + 1 >= argc || starts_with_dashes(argv[i + 1])) fail("option --" + name + " expects a value");
        else value = argv[++i];
        set_value(*e, value);
        e->given = true;
    }
    parsed_ = true;
    for (const auto& check : checks_) check();
}

void Options::check_or_defer(std::function<void()> check)
{
    if (parsed_) check();
    else checks_.push_back(std::move(check));
}

double Options::numeric(const std::string& name) const
{
    const Entry& e = lookup(name);
    if (e.kind == Kind::Real) return e.real;
    if (e.kind == Kind::Int) return e.integer;
    throw std::logic_error(program_ + ": option '" + name + "' is not numeric");
}

// A NaN value can only be a driver's default (the command line rejects it): it means "automatic"
// and passes the checks.
void Options::require_positive(const std::string& name)
{
    numeric(name);  // logic_error now if unknown or not numeric
    check_or_defer([this, name] {
        if (numeric(name) <= 0.0) fail("option --" + name + " must be > 0, got " + lookup(name).value_text());
    });
}

void Options::require_at_least(const std::string& name, double v)
{
    numeric(name);
    check_or_defer([this, name, v] {
        if (numeric(name) < v)
            fail("option --" + name + " must be >= " + format_shortest(v) + ", got " + lookup(name).value_text());
    });
}

void Options::require_range(const std::string& name, double lo, double hi, bool lo_inclusive, bool hi_inclusive)
{
    numeric(name);
    check_or_defer([this, name, lo, hi, lo_inclusive, hi_inclusive] {
        const double x = numeric(name);
        const bool below = lo_inclusive ? x < lo : x <= lo;
        const bool above = hi_inclusive ? x > hi : x >= hi;
        if (below || above)
            fail("option --" + name + " must be in " + (lo_inclusive ? "[" : "(") + format_shortest(lo) +
                 ", " + format_shortest(hi) + (hi_inclusive ? "]" : ")") + ", got " + lookup(name).value_text());
    });
}

double Options::get(const std::string& name) const { return numeric(name); }

void Options::set_default(const std::string& name, double value)
{
    Entry& e = lookup(name);
    if (e.given) return;
    if (e.kind == Kind::Real) e.real = value;
    else if (e.kind == Kind::Int && value == std::trunc(value)) e.integer = static_cast<int>(value);
    else throw std::logic_error(program_ + ": set_default(" + name + "): not a real or an integral int value");
}

void Options::set_default(const std::string& name, const std::string& value)
{
    Entry& e = lookup(name);
    if (e.kind != Kind::String) throw std::logic_error(program_ + ": set_default(" + name + "): not a string option");
    if (!e.given) e.text = value;
}

int Options::get_int(const std::string& name) const
{
    const Entry& e = lookup(name);
    if (e.kind != Kind::Int) throw std::logic_error(program_ + ": option '" + name + "' is not an int");
    return e.integer;
}

std::string Options::get_string(const std::string& name) const
{
    const Entry& e = lookup(name);
    if (e.kind != Kind::String) throw std::logic_error(program_ + ": option '" + name + "' is not a string");
    return e.text;
}

bool Options::get_flag(const std::string& name) const
{
    const Entry& e = lookup(name);
    if (e.kind != Kind::Flag) throw std::logic_error(program_ + ": option '" + name + "' is not a flag");
    return e.flag;
}

bool Options::has(const std::string& name) const { return find(name) != nullptr; }

bool Options::given(const std::string& name) const { return lookup(name).given; }

void Options::echo(std::ostream& os) const
{
    for (const auto& e : entries_) {
        if (!e->recorded) continue;
        os << "  " << e->name << " = " << e->value_text();
        if (!e->unit.empty()) os << " [" << e->unit << "]";
        os << '\n';
    }
}

void Options::not_recorded(const std::string& name) { lookup(name).recorded = false; }

void Options::save_csv(const std::filesystem::path& path) const
{
    CsvWriter csv(path, {"option", "value", "unit"}, false);
    for (const auto& e : entries_)
        if (e->recorded) csv.row_strings({e->name, e->value_text(), e->unit});
    csv.close();
}

void Options::print_usage(std::ostream& os) const
{
    std::vector<std::string> left;
    std::size_t width = 0;
    for (const auto& e : entries_) {
        left.push_back("--" + e->name + e->placeholder());
        width = std::max(width, left.back().size());
    }
    const std::size_t max_width = 28;  // longer option columns wrap the help to the next line
    width = std::min(width, max_width);
    auto line = [&](const std::string& l, const std::string& text) {
        os << "  " << l;
        if (l.size() > width) os << '\n' << std::string(width + 2, ' ');
        else os << std::string(width - l.size(), ' ');
        os << "  " << text << '\n';
    };
    os << "usage: " << program_ << " [options]\n\n" << description_ << "\n\noptions:\n";
    for (std::size_t k = 0; k < entries_.size(); ++k) {
        const Entry& e = *entries_[k];
        std::string text = e.help;
        if (!e.unit.empty()) text += " [" + e.unit + "]";
        if (e.kind != Kind::Flag) text += " (default " + e.default_text + ")";
        line(left[k], text);
    }
    line("--help", "print this help and exit");
}

void Options::fail(const std::string& message) const { fail_input(program_, message); }

void add_standard(Options& opt, const std::string& default_out, const std::string& out_help)
{
    opt.add_flag("quick", "coarse discretisation that runs in seconds");
    opt.add_flag("check", "exit non-zero when the documented tolerance is missed");
    opt.add_string("out", default_out, out_help);
    opt.add_int("threads", 0, "OpenMP threads (0 = OpenMP default)");
    opt.require_at_least("threads", 0);
    opt.add_int("max-steps", 100000000, "refuse a run needing more time steps than this (0 = no limit)");
    opt.require_at_least("max-steps", 0);
}

}  // namespace pd::io
