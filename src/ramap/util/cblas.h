// The CBLAS interface with C linkage. Debian's cblas.h is an alternative: netlib's declares its
// functions extern "C", ATLAS's (chosen when libatlas-base-dev, which libceres-dev pulls in, is
// installed after libblas-dev) does not, and C++ then looks for mangled names no BLAS exports.
#pragma once

extern "C" {
#include <cblas.h>
}
