// The file-level readers and writers of COLMAP's model formats, shared by the model files
// (io/colmap_model.h) and the rig and frame files (io/colmap_model_rigs.h): little-endian binary
// records whose truncation is reported with the item being read, and text lines read with their
// line numbers.
#pragma once

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "ramap/util/error.h"

namespace ramap {

// The whole file at `path`; InputError when it is missing or unreadable.
inline std::string ReadWholeFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "file not found");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path, "cannot open for reading");
  std::string data((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (file.bad()) throw InputError(path, "read failed");
  return data;
}

class BinaryReader {
 public:
  explicit BinaryReader(std::string path) : path_(std::move(path)), data_(ReadWholeFile(path_)) {}

  // What is being read, for the truncation message ("image 3 (of 12)").
  void SetItem(std::string item) { item_ = std::move(item); }
  const std::string& path() const { return path_; }
  size_t remaining() const { return data_.size() - pos_; }

  uint64_t ReadUnsigned(int num_bytes) {
    Need(num_bytes);
    uint64_t value = 0;
    for (int i = 0; i < num_bytes; ++i) {
      value |= static_cast<uint64_t>(static_cast<uint8_t>(data_[pos_ + i])) << (8 * i);
    }
    pos_ += num_bytes;
    return value;
  }
  uint8_t ReadUint8() { return static_cast<uint8_t>(ReadUnsigned(1)); }
  uint32_t ReadUint32() { return static_cast<uint32_t>(ReadUnsigned(4)); }
  int32_t ReadInt32() {
    const uint32_t bits = ReadUint32();
    int32_t value;
    std::memcpy(&value, &bits, sizeof(value));
    return value;
  }
  uint64_t ReadUint64() { return ReadUnsigned(8); }
  double ReadDouble() {
    const uint64_t bits = ReadUint64();
    double value;
    std::memcpy(&value, &bits, sizeof(value));
    return value;
  }
  std::string ReadString() {
    const size_t end = data_.find('\0', pos_);
    if (end == std::string::npos) Truncated();
    std::string value = data_.substr(pos_, end - pos_);
    pos_ = end + 1;
    return value;
  }
  // A count of `count` records of at least `min_bytes` each must fit in what is left; checked
  // before allocating so that a corrupt count fails cleanly.
  void ExpectRecords(uint64_t count, uint64_t min_bytes) {
    if (min_bytes > 0 && count > remaining() / min_bytes) Truncated();
  }
  void ExpectEnd() {
    if (remaining() != 0) {
      throw InputError(path_, std::to_string(remaining()) +
                                  " unexpected bytes after the last record (not a COLMAP "
                                  "model, or a corrupt count)");
    }
  }

 private:
  void Need(size_t num_bytes) {
    if (remaining() < num_bytes) Truncated();
  }
  [[noreturn]] void Truncated() const {
    throw InputError(path_, "truncated while reading " + item_);
  }

  std::string path_;
  std::string data_;
  size_t pos_ = 0;
  std::string item_ = "the header";
};

// Little-endian values, gathered in a buffer and written a mebibyte at a time: one ostream call
// per value made writing a long drive's images.bin slow. The rest is written when the writer
// goes out of scope; stream errors stay in the stream's state for the caller to check.
class BinaryWriter {
 public:
  explicit BinaryWriter(std::ostream& out) : out_(out) { buffer_.reserve(kFlushBytes + 64); }
  ~BinaryWriter() { Flush(); }
  BinaryWriter(const BinaryWriter&) = delete;
  BinaryWriter& operator=(const BinaryWriter&) = delete;

  void WriteUnsigned(uint64_t value, int num_bytes) {
    for (int i = 0; i < num_bytes; ++i)
      buffer_.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
    if (buffer_.size() >= kFlushBytes) Flush();
  }
  void WriteUint8(uint8_t value) { WriteUnsigned(value, 1); }
  void WriteUint32(uint32_t value) { WriteUnsigned(value, 4); }
  void WriteInt32(int32_t value) {
    uint32_t bits;
    std::memcpy(&bits, &value, sizeof(bits));
    WriteUnsigned(bits, 4);
  }
  void WriteUint64(uint64_t value) { WriteUnsigned(value, 8); }
  void WriteDouble(double value) {
    uint64_t bits;
    std::memcpy(&bits, &value, sizeof(bits));
    WriteUnsigned(bits, 8);
  }
  void WriteString(const std::string& value) {
    buffer_.append(value.c_str(), value.size() + 1);
    if (buffer_.size() >= kFlushBytes) Flush();
  }

 private:
  static constexpr size_t kFlushBytes = size_t{1} << 20;

  void Flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }

  std::ostream& out_;
  std::string buffer_;
};

// Text format, as COLMAP writes it: '#' comment header, space-separated fields.
class TextLines {
 public:
  explicit TextLines(const std::string& path) : path_(path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "file not found");
    file_.open(path);
    if (!file_) throw InputError(path, "cannot open for reading");
  }

  // The next line that is neither blank nor a comment; false at the end of the file.
  bool NextDataLine(std::vector<std::string>* tokens) {
    std::string line;
    while (NextLine(&line)) {
      Split(line, tokens);
      if (!tokens->empty() && (*tokens)[0][0] != '#') return true;
    }
    return false;
  }
  // The very next line, whatever it holds (the observations line of an image).
  bool NextRawLine(std::vector<std::string>* tokens) {
    std::string line;
    if (!NextLine(&line)) return false;
    Split(line, tokens);
    return true;
  }

  int line_number() const { return line_number_; }
  const std::string& path() const { return path_; }

  [[noreturn]] void Fail(const std::string& problem) const {
    throw InputError(path_, "line " + std::to_string(line_number_) + ": " + problem);
  }

  double Double(const std::string& token, const std::string& what) const {
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(token.c_str(), &end);
    if (token.empty() || *end != '\0') Fail("cannot read " + what + " from '" + token + "'");
    return value;
  }
  double FiniteDouble(const std::string& token, const std::string& what) const {
    const double value = Double(token, what);
    if (!std::isfinite(value)) Fail(what + " is not a finite number ('" + token + "')");
    return value;
  }
  uint64_t Unsigned(const std::string& token, const std::string& what, uint64_t max) const {
    char* end = nullptr;
    errno = 0;
    const unsigned long long value = std::strtoull(token.c_str(), &end, 10);
    if (token.empty() || token[0] == '-' || token[0] == '+' || *end != '\0' || errno == ERANGE ||
        value > max) {
      Fail("cannot read " + what + " from '" + token + "'");
    }
    return value;
  }

 private:
  bool NextLine(std::string* line) {
    if (!std::getline(file_, *line)) return false;
    ++line_number_;
    if (!line->empty() && line->back() == '\r') line->pop_back();
    return true;
  }
  static void Split(const std::string& line, std::vector<std::string>* tokens) {
    tokens->clear();
    std::istringstream stream(line);
    std::string token;
    while (stream >> token) tokens->push_back(token);
  }

  std::string path_;
  std::ifstream file_;
  int line_number_ = 0;
};

constexpr uint64_t kMaxUint32 = 0xffffffffull;
constexpr uint64_t kMaxUint64 = ~0ull;

// %.17g: what COLMAP 3.8 writes (ostream precision 17), and enough to read back the same double.
inline std::string FormatDouble(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), "%.17g", value);
  return buffer;
}

inline std::string Ordinal(uint64_t index, uint64_t count) {
  return std::to_string(index + 1) + " (of " + std::to_string(count) + ")";
}

}  // namespace ramap
