#include "scene/initial_provenance.hpp"

#include <openssl/evp.h>

#include <array>
#include <fstream>
#include <memory>
#include <stdexcept>

namespace granvv::app {

std::string file_sha256(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  const std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(),
                                                                    &EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("SHA-256 is not available");
  }
  std::array<char, 1 << 16> buffer;
  while (in) {
    in.read(buffer.data(), buffer.size());
    if (in.gcount() > 0) EVP_DigestUpdate(ctx.get(), buffer.data(), std::size_t(in.gcount()));
  }
  if (in.bad()) throw std::runtime_error("cannot read " + file.string());
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_DigestFinal_ex(ctx.get(), digest, &length);
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < length; ++i) {
    out += hex[digest[i] >> 4];
    out += hex[digest[i] & 15];
  }
  return out;
}

nlohmann::json initial_provenance(const hydro::InitialParameters& initial) {
  nlohmann::json files = nlohmann::json::array();
  for (const auto& path : hydro::initial_files(initial)) {
    std::error_code ec;
    const auto absolute = std::filesystem::absolute(path, ec);
    files.push_back({{"path", path},
                     {"absolute_path", ec ? path : absolute.lexically_normal().string()},
                     {"bytes", std::filesystem::file_size(path)},
                     {"sha256", file_sha256(path)}});
  }
  return {{"type", initial.type}, {"files", files}};
}

}  // namespace granvv::app
