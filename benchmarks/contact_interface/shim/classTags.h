// upliftlab stand-in (see Vector.h): the one class tag the section names.
#ifndef classTags_h
#define classTags_h
#define SEC_TAG_SoilFooting2d 1
#endif
