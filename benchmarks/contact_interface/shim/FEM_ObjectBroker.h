// upliftlab stand-in (see Vector.h): nothing of it is used by the section.
#ifndef FEM_ObjectBroker_h
#define FEM_ObjectBroker_h
class FEM_ObjectBroker;
#endif
