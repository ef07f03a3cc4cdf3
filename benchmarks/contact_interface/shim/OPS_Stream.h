// upliftlab's stand-in (see Vector.h): OpenSees's message stream, written to stderr.
#ifndef OPS_Stream_h
#define OPS_Stream_h

#include <cstdio>
#include "Vector.h"

class OPS_Stream {
 public:
  OPS_Stream &operator<<(const char *text) {
    std::fputs(text, stderr);
    return *this;
  }
  OPS_Stream &operator<<(int value) {
    std::fprintf(stderr, "%d", value);
    return *this;
  }
  OPS_Stream &operator<<(double value) {
    std::fprintf(stderr, "%.17g", value);
    return *this;
  }
  OPS_Stream &operator<<(const Vector &v) {
    for (int i = 0; i < v.Size(); i++) std::fprintf(stderr, " %.17g", v(i));
    std::fputs("\n", stderr);
    return *this;
  }
  OPS_Stream &operator<<(OPS_Stream &(*manipulator)(OPS_Stream &)) { return manipulator(*this); }
};

inline OPS_Stream &endln(OPS_Stream &stream) { return stream << "\n"; }
extern OPS_Stream opserr;

#endif
