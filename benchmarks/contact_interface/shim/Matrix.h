// upliftlab's stand-in (see Vector.h): a matrix of at most 3 x 3 numbers.
#ifndef Matrix_h
#define Matrix_h

#include <cstdlib>
#include "Vector.h"

class Matrix {
 public:
  Matrix(int rows = 0, int columns = 0) : rows_(rows), columns_(columns) {
    if (rows < 0 || rows > 3 || columns < 0 || columns > 3) std::abort();
    Zero();
  }
  int noRows() const { return rows_; }
  int noCols() const { return columns_; }
  void Zero() {
    for (int i = 0; i < 9; i++) data_[i] = 0.0;
  }
  double &operator()(int i, int j) { return data_[at(i, j)]; }
  double operator()(int i, int j) const { return data_[at(i, j)]; }
  Vector operator*(const Vector &v) const {
    if (v.Size() != columns_) std::abort();
    Vector out(rows_);
    for (int i = 0; i < rows_; i++) {
      double sum = 0.0;
      for (int j = 0; j < columns_; j++) sum += data_[at(i, j)] * v(j);
      out(i) = sum;
    }
    return out;
  }

 private:
  int at(int i, int j) const {
    if (i < 0 || i >= rows_ || j < 0 || j >= columns_) std::abort();
    return 3 * i + j;
  }
  int rows_, columns_;
  double data_[9];
};

#endif
