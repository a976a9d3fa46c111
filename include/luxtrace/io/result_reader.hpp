#pragma once
// Reading a result or checkpoint file back by HDF5 path, for `luxtrace info` and for tests;
// other readers use the typed ResultFile (result_data.hpp), which reads through this class.
// The file's seal (file_seal.hpp) is checked before HDF5 parses a byte of it.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace luxtrace {

class ResultReader {
public:
    explicit ResultReader(const std::filesystem::path& path);  // throws InputError
    ~ResultReader();
    ResultReader(const ResultReader&) = delete;
    ResultReader& operator=(const ResultReader&) = delete;

    bool has(const std::string& object) const;
    bool has_attr(const std::string& object, const std::string& name) const;
    std::vector<std::uint64_t> u64(const std::string& dataset, std::vector<std::size_t>* shape = nullptr) const;
    std::vector<double> f64(const std::string& dataset, std::vector<std::size_t>* shape = nullptr) const;
    double attr_f64(const std::string& object, const std::string& name) const;
    std::vector<double> f64_attr_array(const std::string& object, const std::string& name) const;
    std::uint64_t attr_u64(const std::string& object, const std::string& name) const;
    std::string attr_str(const std::string& object, const std::string& name) const;
    std::vector<std::string> attr_strs(const std::string& object, const std::string& name) const;
    std::vector<std::string> children(const std::string& group) const;
    const std::filesystem::path& path() const { return path_; }
    // The file carries luxtrace's seal (file_seal.hpp) and matched it.
    bool sealed() const { return sealed_; }

private:
    std::filesystem::path path_;
    bool sealed_ = false;
    std::int64_t file_ = -1;  // hid_t
};

}  // namespace luxtrace
