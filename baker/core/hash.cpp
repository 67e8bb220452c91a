// SHA-256 through OpenSSL's EVP interface (it picks the CPU's SHA instructions where there are some).
#include "core/hash.h"

#include <openssl/evp.h>

#include <cstdint>
#include <stdexcept>

namespace qf {

struct Sha256::State {
  EVP_MD_CTX* ctx = nullptr;
};

Sha256::Sha256() : state_(std::make_unique<State>()) {
  state_->ctx = EVP_MD_CTX_new();
  if (!state_->ctx || EVP_DigestInit_ex(state_->ctx, EVP_sha256(), nullptr) != 1) throw std::runtime_error("OpenSSL: cannot start SHA-256");
}

Sha256::~Sha256() { EVP_MD_CTX_free(state_->ctx); }

Sha256& Sha256::update(ByteView bytes) {
  if (!bytes.empty()) EVP_DigestUpdate(state_->ctx, bytes.data(), bytes.size());
  return *this;
}

Sha256& Sha256::update_field(const std::string& s) {
  const std::uint64_t n = s.size();
  std::uint8_t len[8];
  for (int i = 0; i < 8; ++i) len[i] = static_cast<std::uint8_t>(n >> (8 * i));
  update(ByteView(len, 8));
  return update(ByteView(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()));
}

std::uint64_t Sha256::digest64() {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int n = 0;
  EVP_DigestFinal_ex(state_->ctx, digest, &n);
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v = v << 8 | digest[i];
  return v;
}

std::string Sha256::hex() {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int n = 0;
  EVP_DigestFinal_ex(state_->ctx, digest, &n);
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < n; ++i) out += digits[digest[i] >> 4], out += digits[digest[i] & 15];
  return out;
}

std::string sha256_of_file(const std::string& path) {
  const InputFile f(path);
  return Sha256().update(f.bytes()).hex();
}

}  // namespace qf
