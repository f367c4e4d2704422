// Thin RAII wrappers over SQLite3's C API: a connection and a prepared statement.
//
// Every failure throws InputError naming `source` (the database file as the user gave it, which
// may differ from the path actually opened, e.g. a staged temporary file) and SQLite's message.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

struct sqlite3;
struct sqlite3_stmt;

namespace ramap::sqlite {

// An open database; closed when destroyed.
// How long a statement waits for another connection's lock before failing.
constexpr int kBusyTimeoutMs = 10000;

class Connection {
 public:
  // `flags` are sqlite3_open_v2 flags; see OpenExisting() / Create().
  Connection(const std::string& path, int flags, std::string source);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  // Opens an existing database for reading; pair with SetQueryOnly(). Read-write on purpose: a
  // read-only connection to a WAL-mode database (as COLMAP leaves them) creates -wal and -shm
  // files beside it that it cannot remove, while a read-write one removes them when it closes. A
  // file the user cannot write is still opened, read-only.
  static int OpenExisting();
  // Opens for writing, creating the file when absent.
  static int Create();

  sqlite3* get() const { return db_; }
  const std::string& source() const { return source_; }

  // Makes any statement that would change the database fail.
  void SetQueryOnly() { Execute("PRAGMA query_only = 1"); }
  // Runs one or more statements that return no rows of interest.
  void Execute(const std::string& sql);
  // SQLite's message about the last failure on this connection.
  std::string LastError() const;
  // Throws InputError(source(), what + ": " + SQLite's last message).
  [[noreturn]] void Fail(const std::string& what) const;

 private:
  sqlite3* db_ = nullptr;
  std::string source_;
};

// A bytes view of a BLOB column: valid until the statement steps or is reset.
struct BlobView {
  const void* data = nullptr;
  size_t size = 0;
};

// A prepared statement, finalized when destroyed. Bind indices are 1-based (as SQLite's),
// column indices 0-based.
class Statement {
 public:
  Statement(Connection& connection, const std::string& sql);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  // Advances: true when a row is available, false when done.
  bool Step();
  // Steps once and expects no row (INSERT/UPDATE), then resets for the next use.
  void Run();
  // Ready for new bindings and steps.
  void Reset();

  void BindInt64(int index, int64_t value);
  // NaN binds as NULL (SQLite would store it so anyway).
  void BindDouble(int index, double value);
  void BindNull(int index);
  void BindText(int index, const std::string& value);
  // Copies the bytes (SQLITE_TRANSIENT) so the caller's buffer may go away before stepping.
  void BindBlob(int index, const void* data, size_t size);

  bool IsNull(int column) const;
  int64_t ColumnInt64(int column) const;
  double ColumnDouble(int column) const;
  std::string ColumnText(int column) const;
  BlobView ColumnBlob(int column) const;

 private:
  Connection& connection_;
  std::string sql_;
  sqlite3_stmt* statement_ = nullptr;
};

}  // namespace ramap::sqlite
