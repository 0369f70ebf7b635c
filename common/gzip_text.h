// gzip (RFC 1952) of whole text files, through zlib: contacts.csv.gz (nmm-solve --contacts-gzip)
// and any reader of it. A .gz file is the same CSV, readable by zcat, Python's gzip module and
// pandas.read_csv; numeric CSV shrinks about threefold (a tunnel run's contacts: 891 kB → 263 kB).
#pragma once

#include <string>

namespace nmm {

/// The gzip member of `text` (deflate level 6, no file name, mtime 0: same input, same bytes).
std::string gzip_compress(const std::string& text);

/// True if `bytes` starts with the gzip magic (1f 8b).
bool is_gzip(const std::string& bytes);

/// The text of a gzip file's contents. InputError(name, "byte N", what) when damaged.
std::string gzip_decompress(const std::string& bytes, const std::string& name);

}  // namespace nmm
