#pragma once
// SHA-256 (FIPS 180-4) of bytes and of files: the checksums that tell a
// batch run whether an input has changed since its record was written.
#include <cstddef>
#include <cstdint>
#include <string>

namespace dfrecon {

/// Incremental SHA-256: add() bytes in any pieces, then hex() once. O(bytes).
class Sha256 {
  public:
    Sha256();
    void add(const void* data, std::size_t bytes);
    /// The digest as 64 lowercase hex digits; the object is spent after.
    std::string hex();

  private:
    void compress(const unsigned char* block);
    std::uint32_t state_[8];
    unsigned char buffer_[64];
    std::size_t buffered_ = 0;
    std::uint64_t totalBytes_ = 0;
};

/// SHA-256 of `bytes` as 64 lowercase hex digits. O(bytes).
std::string sha256Hex(const std::string& bytes);

/// SHA-256 of the file's bytes, read in 1 MiB pieces (memory O(1)); throws
/// InputError "PATH: cannot read file" when it cannot be opened or read.
/// O(file size).
std::string sha256OfFile(const std::string& path);

}  // namespace dfrecon
