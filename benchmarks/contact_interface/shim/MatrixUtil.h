// upliftlab stand-in (see Vector.h): nothing of it is used by the section.
#ifndef MatrixUtil_h
#define MatrixUtil_h
#endif
