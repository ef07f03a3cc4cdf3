// upliftlab's stand-in (see Vector.h): the base of OpenSees's sections, with only what the
// contact interface model's class needs to compile and to be driven through its own methods.
#ifndef SectionForceDeformation_h
#define SectionForceDeformation_h

#include "ID.h"
#include "Matrix.h"
#include "OPS_Stream.h"
#include "Vector.h"

class Channel;
class FEM_ObjectBroker;
class Information;

const int SECTION_RESPONSE_MZ = 1;
const int SECTION_RESPONSE_P = 2;
const int SECTION_RESPONSE_VY = 3;

class SectionForceDeformation {
 public:
  SectionForceDeformation(int tag, int class_tag) : tag_(tag), class_tag_(class_tag) {}
  virtual ~SectionForceDeformation() {}
  int getTag() const { return tag_; }
  int getClassTag() const { return class_tag_; }

 private:
  int tag_, class_tag_;
};

#endif
