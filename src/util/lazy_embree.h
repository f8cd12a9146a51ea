/* Embree, bound on first use (util/lazylib.h): include this instead of <embree3/rtcore.h>. */
#ifndef SYL_UTIL_LAZY_EMBREE_H
#define SYL_UTIL_LAZY_EMBREE_H

#include <embree3/rtcore.h>

#include "util/lazylib.h"

#define EMBREE_FUNCS(X)                                                                          \
    X(rtcAttachGeometry) X(rtcAttachGeometryByID) X(rtcCommitGeometry) X(rtcCommitScene)         \
    X(rtcGetDeviceError) X(rtcGetGeometry) X(rtcIntersect1) X(rtcIntersect16) X(rtcNewDevice)    \
    X(rtcNewGeometry) X(rtcNewScene) X(rtcOccluded1) X(rtcOccluded16) X(rtcReleaseDevice)        \
    X(rtcReleaseGeometry) X(rtcReleaseScene) X(rtcSetDeviceErrorFunction)                        \
    X(rtcSetGeometryInstancedScene) X(rtcSetGeometryIntersectFilterFunction)                     \
    X(rtcSetGeometryOccludedFilterFunction) X(rtcSetGeometryTransform)                           \
    X(rtcSetGeometryUserData) X(rtcSetSceneBuildQuality) X(rtcSetSceneFlags)                     \
    X(rtcSetSharedGeometryBuffer)

typedef struct EmbreeApi {
    EMBREE_FUNCS(LAZY_LIB_FIELD)
} EmbreeApi;
const EmbreeApi *embree_api(void);

/* Each call goes through the table; a function missing here is an undefined symbol at link. */
#define rtcAttachGeometry(...) embree_api()->rtcAttachGeometry(__VA_ARGS__)
#define rtcAttachGeometryByID(...) embree_api()->rtcAttachGeometryByID(__VA_ARGS__)
#define rtcCommitGeometry(...) embree_api()->rtcCommitGeometry(__VA_ARGS__)
#define rtcCommitScene(...) embree_api()->rtcCommitScene(__VA_ARGS__)
#define rtcGetDeviceError(...) embree_api()->rtcGetDeviceError(__VA_ARGS__)
#define rtcGetGeometry(...) embree_api()->rtcGetGeometry(__VA_ARGS__)
#define rtcIntersect1(...) embree_api()->rtcIntersect1(__VA_ARGS__)
#define rtcIntersect16(...) embree_api()->rtcIntersect16(__VA_ARGS__)
#define rtcNewDevice(...) embree_api()->rtcNewDevice(__VA_ARGS__)
#define rtcNewGeometry(...) embree_api()->rtcNewGeometry(__VA_ARGS__)
#define rtcNewScene(...) embree_api()->rtcNewScene(__VA_ARGS__)
#define rtcOccluded1(...) embree_api()->rtcOccluded1(__VA_ARGS__)
#define rtcOccluded16(...) embree_api()->rtcOccluded16(__VA_ARGS__)
#define rtcReleaseDevice(...) embree_api()->rtcReleaseDevice(__VA_ARGS__)
#define rtcReleaseGeometry(...) embree_api()->rtcReleaseGeometry(__VA_ARGS__)
#define rtcReleaseScene(...) embree_api()->rtcReleaseScene(__VA_ARGS__)
#define rtcSetDeviceErrorFunction(...) embree_api()->rtcSetDeviceErrorFunction(__VA_ARGS__)
#define rtcSetGeometryInstancedScene(...) embree_api()->rtcSetGeometryInstancedScene(__VA_ARGS__)
#define rtcSetGeometryIntersectFilterFunction(...) embree_api()->rtcSetGeometryIntersectFilterFunction(__VA_ARGS__)
#define rtcSetGeometryOccludedFilterFunction(...) embree_api()->rtcSetGeometryOccludedFilterFunction(__VA_ARGS__)
#define rtcSetGeometryTransform(...) embree_api()->rtcSetGeometryTransform(__VA_ARGS__)
#define rtcSetGeometryUserData(...) embree_api()->rtcSetGeometryUserData(__VA_ARGS__)
#define rtcSetSceneBuildQuality(...) embree_api()->rtcSetSceneBuildQuality(__VA_ARGS__)
#define rtcSetSceneFlags(...) embree_api()->rtcSetSceneFlags(__VA_ARGS__)
#define rtcSetSharedGeometryBuffer(...) embree_api()->rtcSetSharedGeometryBuffer(__VA_ARGS__)

#endif
