// upliftlab's stand-in (see Vector.h): a list of at most three integers.
#ifndef ID_h
#define ID_h

#include <cstdlib>

class ID {
 public:
  explicit ID(int size = 0) : size_(size) {
    if (size < 0 || size > 3) std::abort();
    for (int i = 0; i < 3; i++) data_[i] = 0;
  }
  int &operator()(int i) {
    if (i < 0 || i >= size_) std::abort();
    return data_[i];
  }

 private:
  int size_;
  int data_[3];
};

#endif
