// The SQLite wrappers: values bound and read back by type, NaN stored as NULL, statements reused
// after Run, and every failure an InputError naming the source given rather than the path opened.
#include "ramap/io/sqlite.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

using sqlite::Connection;
using sqlite::Statement;

TEST(Sqlite, ValuesReadBackAsBound) {
  test::TempDir dir;
  Connection db(dir / "values.db", Connection::Create(), "values.db");
  db.Execute("CREATE TABLE t (i INTEGER, r REAL, s TEXT, b BLOB, n)");
  const double numbers[3] = {1.5, -2.25, 1e300};
  {
    Statement insert(db, "INSERT INTO t VALUES (?, ?, ?, ?, ?)");
    insert.BindInt64(1, std::numeric_limits<int64_t>::max());
    insert.BindDouble(2, -0.1);
    insert.BindText(3, std::string("a\0b", 3));  // text with a NUL byte survives whole
    insert.BindBlob(4, numbers, sizeof(numbers));
    insert.BindNull(5);
    insert.Run();
  }
  Statement select(db, "SELECT i, r, s, b, n FROM t");
  ASSERT_TRUE(select.Step());
  EXPECT_EQ(select.ColumnInt64(0), std::numeric_limits<int64_t>::max());
  EXPECT_EQ(select.ColumnDouble(1), -0.1);
  EXPECT_EQ(select.ColumnText(2), std::string("a\0b", 3));
  const sqlite::BlobView blob = select.ColumnBlob(3);
  ASSERT_EQ(blob.size, sizeof(numbers));
  EXPECT_EQ(std::memcmp(blob.data, numbers, sizeof(numbers)), 0);
  EXPECT_TRUE(select.IsNull(4));
  EXPECT_FALSE(select.IsNull(0));
  EXPECT_FALSE(select.Step());  // one row only
}

TEST(Sqlite, NanIsStoredAsNullAndAnEmptyBlobIsNotNull) {
  test::TempDir dir;
  Connection db(dir / "nan.db", Connection::Create(), "nan.db");
  db.Execute("CREATE TABLE t (r REAL, b BLOB)");
  {
    Statement insert(db, "INSERT INTO t VALUES (?, ?)");
    insert.BindDouble(1, std::numeric_limits<double>::quiet_NaN());
    insert.BindBlob(2, nullptr, 0);
    insert.Run();
  }
  Statement select(db, "SELECT r IS NULL, b IS NULL, length(b) FROM t");
  ASSERT_TRUE(select.Step());
  EXPECT_EQ(select.ColumnInt64(0), 1);
  EXPECT_EQ(select.ColumnInt64(1), 0);  // zero bytes, as COLMAP stores an empty matrix
  EXPECT_EQ(select.ColumnInt64(2), 0);
}

TEST(Sqlite, RunResetsTheStatementForItsNextBindings) {
  test::TempDir dir;
  Connection db(dir / "run.db", Connection::Create(), "run.db");
  db.Execute("CREATE TABLE t (i INTEGER)");
  Statement insert(db, "INSERT INTO t VALUES (?)");
  for (int64_t k = 0; k < 5; ++k) {
    insert.BindInt64(1, k * k);
    insert.Run();
  }
  Statement sum(db, "SELECT count(*), sum(i) FROM t");
  ASSERT_TRUE(sum.Step());
  EXPECT_EQ(sum.ColumnInt64(0), 5);
  EXPECT_EQ(sum.ColumnInt64(1), 0 + 1 + 4 + 9 + 16);
  // Reset lets a query run again from its first row.
  sum.Reset();
  ASSERT_TRUE(sum.Step());
  EXPECT_EQ(sum.ColumnInt64(0), 5);
}

TEST(Sqlite, FailuresNameTheSourceNotThePathOpened) {
  test::TempDir dir;
  // The file actually opened is a staged copy; messages name what the user gave.
  Connection db(dir / "staged.tmp", Connection::Create(), "project/database.db");
  db.Execute("CREATE TABLE t (i INTEGER NOT NULL)");
  test::ExpectInputError([&] { db.Execute("SELECT * FROM no_such_table"); },
                         {"project/database.db", "no such table: no_such_table"});
  test::ExpectInputError([&] { Statement(db, "SELEKT 1"); },
                         {"project/database.db", "cannot prepare 'SELEKT 1'"});
  test::ExpectInputError(
      [&] {
        Statement insert(db, "INSERT INTO t VALUES (?)");
        insert.BindNull(1);
        insert.Run();
      },
      {"project/database.db", "NOT NULL constraint failed"});
  test::ExpectInputError([&] { Statement(db, "SELECT 1").Run(); },
                         {"project/database.db", "'SELECT 1' returned rows"});
  test::ExpectInputError([&] { db.Fail("reading keypoints"); },
                         {"project/database.db", "reading keypoints"});
}

TEST(Sqlite, QueryOnlyRefusesChanges) {
  test::TempDir dir;
  {
    Connection db(dir / "read.db", Connection::Create(), "read.db");
    db.Execute("CREATE TABLE t (i INTEGER); INSERT INTO t VALUES (7)");
  }
  Connection db(dir / "read.db", Connection::OpenExisting(), "read.db");
  db.SetQueryOnly();
  Statement select(db, "SELECT i FROM t");
  ASSERT_TRUE(select.Step());
  EXPECT_EQ(select.ColumnInt64(0), 7);
  test::ExpectInputError([&] { db.Execute("INSERT INTO t VALUES (8)"); }, {"read.db"});
}

TEST(Sqlite, FilesThatAreNoDatabaseAreRefused) {
  test::TempDir dir;
  // OpenExisting does not create a missing file.
  test::ExpectInputError(
      [&] { Connection(dir / "missing.db", Connection::OpenExisting(), "missing.db"); },
      {"missing.db", "cannot open as an SQLite database"});
  std::ofstream(dir / "text.db") << "this is plain text, long enough to fill a page header........"
                                 << std::string(200, 'x');
  test::ExpectInputError(
      [&] {
        Connection db(dir / "text.db", Connection::OpenExisting(), "text.db");
        db.Execute("SELECT * FROM sqlite_master");
      },
      {"text.db", "not a database"});
}

}  // namespace
}  // namespace ramap
