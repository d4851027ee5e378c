// lib/pd/core/state_archive.cpp -- see state_archive.hpp.
#include "pd/core/state_archive.hpp"

#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <system_error>

namespace pd {

namespace {
constexpr char magic[] = "pd checkpoint 1\n";
constexpr char end_marker[] = "end of checkpoint\n";

template <class T>
std::string to_bytes(const std::vector<T>& v)
{
    return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}
template <class T>
std::string to_bytes(const T& x)
{
    return std::string(reinterpret_cast<const char*>(&x), sizeof(T));
}
void put_u64(std::string& s, std::uint64_t x) { s += to_bytes(x); }
}  // namespace

void StateArchive::fail(const std::string& what) const
{
    throw std::invalid_argument("checkpoint " + (path_.empty() ? std::string("(in memory)") : path_.string()) + ": " + what);
}

void StateArchive::put(const std::string& name, Entry entry)
{
    if (!entries_.emplace(name, std::move(entry)).second)
        throw std::logic_error("checkpoint: two parts of the run save an entry named '" + name + "'");
}

const StateArchive::Entry& StateArchive::find(const std::string& name, Type type) const
{
    const auto it = entries_.find(name);
    if (it == entries_.end()) fail("no entry '" + name + "' (a checkpoint of another kind of run)");
    if (it->second.type != type) fail("entry '" + name + "' has another type");
    return it->second;
}

template <class T>
static void visit_vector(StateArchive::Mode mode, std::vector<T>& v, std::string& stored, const std::string& name,
                         const std::function<void(const std::string&)>& fail)
{
    if (mode == StateArchive::Mode::save) {
        stored = to_bytes(v);
        return;
    }
    if (stored.size() % sizeof(T) != 0) fail("entry '" + name + "' is cut");
    const std::size_t n = stored.size() / sizeof(T);
    if (!v.empty() && v.size() != n)
        fail("entry '" + name + "' has " + std::to_string(n) + " values, the run has " + std::to_string(v.size()) +
             " (a checkpoint of another scene)");
    v.resize(n);
    if (n > 0) std::memcpy(v.data(), stored.data(), stored.size());
}

#define PD_ARCHIVE_VECTOR(T, TYPE)                                                                          \
    void StateArchive::operator()(const std::string& name, std::vector<T>& v)                               \
    {                                                                                                      \
        std::string bytes;                                                                                 \
        if (!saving()) bytes = find(name, TYPE).bytes;                                                     \
        visit_vector(mode_, v, bytes, name, [this](const std::string& w) { fail(w); });                    \
        if (saving()) put(name, {TYPE, std::move(bytes)});                                                 \
    }
PD_ARCHIVE_VECTOR(double, Type::real)
PD_ARCHIVE_VECTOR(std::uint8_t, Type::byte)
#undef PD_ARCHIVE_VECTOR

void StateArchive::operator()(const std::string& name, double& x)
{
    std::vector<double> v{x};
    (*this)(name, v);
    if (v.size() != 1) fail("entry '" + name + "' is not one number");
    x = v[0];
}

void StateArchive::operator()(const std::string& name, long& x)
{
    if (saving()) {
        put(name, {Type::integer, to_bytes(static_cast<std::int64_t>(x))});
        return;
    }
    const Entry& e = find(name, Type::integer);
    if (e.bytes.size() != sizeof(std::int64_t)) fail("entry '" + name + "' is not one integer");
    std::int64_t v = 0;
    std::memcpy(&v, e.bytes.data(), sizeof v);
    x = static_cast<long>(v);
}

void StateArchive::operator()(const std::string& name, std::string& s)
{
    if (saving()) put(name, {Type::text, s});
    else s = find(name, Type::text).bytes;
}

void StateArchive::write(const std::filesystem::path& path) const
{
    std::string data(magic);
    put_u64(data, entries_.size());
    for (const auto& [name, e] : entries_) {
        put_u64(data, name.size());
        data += name;
        data += static_cast<char>(e.type);
        put_u64(data, e.bytes.size());
        data += e.bytes;
    }
    data += end_marker;
    std::filesystem::path part = path;
    part += ".part";
    {
        std::ofstream os(part, std::ios::binary | std::ios::trunc);
        os.write(data.data(), static_cast<std::streamsize>(data.size()));
        os.flush();
        if (!os) throw std::runtime_error("cannot write the checkpoint " + part.string());
    }
    std::error_code ec;
    std::filesystem::rename(part, path, ec);
    if (ec) throw std::runtime_error("cannot rename " + part.string() + " to " + path.string() + ": " + ec.message());
}

StateArchive StateArchive::read(const std::filesystem::path& path)
{
    StateArchive ar;
    ar.mode_ = Mode::load;
    ar.path_ = path;
    std::ifstream is(path, std::ios::binary);
    if (!is) ar.fail("cannot open the file");
    const std::string data((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
    std::size_t at = 0;
    auto take = [&](std::size_t n) {
        if (n > data.size() - at) ar.fail("the file is cut or not a checkpoint");
        const std::string s = data.substr(at, n);
        at += n;
        return s;
    };
    auto take_u64 = [&] {
        std::uint64_t x = 0;
        const std::string s = take(sizeof x);
        std::memcpy(&x, s.data(), sizeof x);
        return x;
    };
    if (data.size() < sizeof magic - 1 || take(sizeof magic - 1) != magic) ar.fail("not a pd checkpoint (no header line)");
    const std::uint64_t count = take_u64();
    for (std::uint64_t q = 0; q < count; ++q) {
        const std::string name = take(take_u64());
        const auto type = static_cast<Type>(take(1)[0]);
        if (type != Type::real && type != Type::byte && type != Type::integer && type != Type::text)
            ar.fail("entry '" + name + "' has an unknown type");
        ar.entries_[name] = {type, take(take_u64())};
    }
    if (take(sizeof end_marker - 1) != end_marker || at != data.size()) ar.fail("the file is cut or has trailing bytes");
    return ar;
}

}  // namespace pd
