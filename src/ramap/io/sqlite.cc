#include "ramap/io/sqlite.h"

#include <sqlite3.h>

#include <cmath>
#include <utility>

#include "ramap/util/error.h"

namespace ramap::sqlite {

Connection::Connection(const std::string& path, int flags, std::string source)
    : source_(std::move(source)) {
  const int rc = sqlite3_open_v2(path.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    const std::string message = db_ != nullptr ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close_v2(db_);
    db_ = nullptr;
    throw InputError(source_, "cannot open as an SQLite database: " + message);
  }
  // Extended codes tell "not a database" apart from I/O errors.
  sqlite3_extended_result_codes(db_, 1);
  // Another process's lock (a writer, or the last reader of a WAL database checkpointing it as it
  // closes, as when two mapper runs share a database) is waited out, not an error.
  sqlite3_busy_timeout(db_, kBusyTimeoutMs);
}

Connection::~Connection() { sqlite3_close_v2(db_); }

int Connection::OpenExisting() { return SQLITE_OPEN_READWRITE; }

int Connection::Create() { return SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE; }

void Connection::Execute(const std::string& sql) {
  char* error = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string message = error != nullptr ? error : sqlite3_errmsg(db_);
    sqlite3_free(error);
    throw InputError(source_, "SQLite error: " + message + " (in: " + sql.substr(0, 80) + ")");
  }
}

std::string Connection::LastError() const { return sqlite3_errmsg(db_); }

void Connection::Fail(const std::string& what) const {
  throw InputError(source_, what + ": " + sqlite3_errmsg(db_));
}

Statement::Statement(Connection& connection, const std::string& sql)
    : connection_(connection), sql_(sql) {
  if (sqlite3_prepare_v2(connection_.get(), sql.c_str(), -1, &statement_, nullptr) != SQLITE_OK) {
    connection_.Fail("SQLite cannot prepare '" + sql + "'");
  }
}

Statement::~Statement() { sqlite3_finalize(statement_); }

bool Statement::Step() {
  const int rc = sqlite3_step(statement_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  connection_.Fail("SQLite failed running '" + sql_ + "'");
}

void Statement::Run() {
  if (Step()) connection_.Fail("'" + sql_ + "' returned rows");
  Reset();
}

void Statement::Reset() {
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
}

namespace {

void Check(Connection& connection, int rc, const char* what) {
  if (rc != SQLITE_OK) connection.Fail(std::string("SQLite cannot bind ") + what);
}

}  // namespace

void Statement::BindInt64(int index, int64_t value) {
  Check(connection_, sqlite3_bind_int64(statement_, index, value), "an integer");
}

void Statement::BindDouble(int index, double value) {
  if (std::isnan(value)) return BindNull(index);
  Check(connection_, sqlite3_bind_double(statement_, index, value), "a real");
}

void Statement::BindNull(int index) {
  Check(connection_, sqlite3_bind_null(statement_, index), "NULL");
}

void Statement::BindText(int index, const std::string& value) {
  Check(connection_,
        sqlite3_bind_text64(statement_, index, value.data(), value.size(), SQLITE_TRANSIENT,
                            SQLITE_UTF8),
        "a text");
}

void Statement::BindBlob(int index, const void* data, size_t size) {
  // A zero-length blob (not NULL) for empty data, as COLMAP stores empty matrices.
  const int rc = size == 0 ? sqlite3_bind_zeroblob(statement_, index, 0)
                           : sqlite3_bind_blob64(statement_, index, data, size, SQLITE_TRANSIENT);
  Check(connection_, rc, "a blob");
}

bool Statement::IsNull(int column) const {
  return sqlite3_column_type(statement_, column) == SQLITE_NULL;
}

int64_t Statement::ColumnInt64(int column) const {
  return sqlite3_column_int64(statement_, column);
}

double Statement::ColumnDouble(int column) const {
  return sqlite3_column_double(statement_, column);
}

std::string Statement::ColumnText(int column) const {
  const unsigned char* text = sqlite3_column_text(statement_, column);
  const int size = sqlite3_column_bytes(statement_, column);
  return text == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(text), size);
}

BlobView Statement::ColumnBlob(int column) const {
  BlobView blob;
  blob.data = sqlite3_column_blob(statement_, column);
  // Bytes after the pointer, as the SQLite documentation asks.
  blob.size =
      blob.data == nullptr ? 0 : static_cast<size_t>(sqlite3_column_bytes(statement_, column));
  return blob;
}

}  // namespace ramap::sqlite
