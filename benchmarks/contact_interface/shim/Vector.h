// upliftlab's stand-in for the few OpenSees classes that SoilFootingSection2d.cpp uses, so that
// the section can be compiled from an OpenSees source tree on its own (benchmarks/
// contact_interface.py). Written for this purpose, not taken from OpenSees: a vector of at most
// three numbers with the operations the section calls.
#ifndef Vector_h
#define Vector_h

#include <cstdlib>

class Vector {
 public:
  explicit Vector(int size = 0) : size_(size) {
    if (size < 0 || size > 3) std::abort();
    for (int i = 0; i < 3; i++) data_[i] = 0.0;
  }
  int Size() const { return size_; }
  void Zero() {
    for (int i = 0; i < 3; i++) data_[i] = 0.0;
  }
  double &operator()(int i) { return data_[check(i)]; }
  double operator()(int i) const { return data_[check(i)]; }
  Vector operator+(const Vector &other) const {
    Vector out(size_);
    for (int i = 0; i < size_; i++) out.data_[i] = data_[i] + other(i);
    return out;
  }
  Vector operator-(const Vector &other) const {
    Vector out(size_);
    for (int i = 0; i < size_; i++) out.data_[i] = data_[i] - other(i);
    return out;
  }

 private:
  int check(int i) const {
    if (i < 0 || i >= size_) std::abort();
    return i;
  }
  int size_;
  double data_[3];
};

#endif
