// gzip of whole files: see gzip_text.h. zlib's deflate with windowBits 15 + 16 writes the gzip
// wrapper (header, CRC-32, length); inflate with 15 + 16 reads it and checks both, so a damaged
// or truncated file is an error, never a silently short table.
#include "common/gzip_text.h"

#include <zlib.h>

#include <stdexcept>

#include "common/error.h"

namespace nmm {

std::string gzip_compress(const std::string& text) {
  z_stream z{};
  if (deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("zlib deflateInit2 failed");
  std::string out(deflateBound(&z, static_cast<uLong>(text.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  z.avail_in = static_cast<uInt>(text.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&z, Z_FINISH);
  const std::size_t n = z.total_out;
  deflateEnd(&z);
  if (rc != Z_STREAM_END) throw std::runtime_error("zlib deflate did not finish");
  out.resize(n);
  return out;
}

bool is_gzip(const std::string& bytes) {
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
         static_cast<unsigned char>(bytes[1]) == 0x8b;
}

std::string gzip_decompress(const std::string& bytes, const std::string& name) {
  z_stream z{};
  if (inflateInit2(&z, 15 + 16) != Z_OK) throw std::runtime_error("zlib inflateInit2 failed");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  z.avail_in = static_cast<uInt>(bytes.size());
  std::string out;
  char buf[1 << 16];
  int rc = Z_OK;
  while (rc == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(buf);
    z.avail_out = sizeof buf;
    rc = inflate(&z, Z_NO_FLUSH);
    out.append(buf, sizeof buf - z.avail_out);
    if (rc == Z_BUF_ERROR && z.avail_in == 0) break;  // input ended before the stream did
  }
  const std::size_t at = z.total_in;
  const std::string msg = z.msg ? z.msg : "inflate error";
  inflateEnd(&z);
  if (rc != Z_STREAM_END)
    throw InputError(name, "byte " + std::to_string(at),
                     rc == Z_BUF_ERROR ? "gzip data ends early (truncated file)"
                                       : "damaged gzip data (" + msg + ")");
  return out;
}

}  // namespace nmm
