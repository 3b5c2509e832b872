// Host-device portability: SM_HD marks functions that run on the CPU and, under nvcc, on the GPU.
// Inside SM_HD code: no virtuals, heap, std containers, exceptions, I/O or statics.
#pragma once
#include <cmath>

#if defined(__CUDACC__)
#define SM_HD __host__ __device__ inline
#else
#define SM_HD inline
#endif

namespace spreadmap {

inline constexpr double pi = 3.14159265358979323846;

template <class T> SM_HD T min(T a, T b) { return a < b ? a : b; }
template <class T> SM_HD T max(T a, T b) { return a > b ? a : b; }
template <class T> SM_HD T clamp(T v, T lo, T hi) { return v < lo ? lo : (v > hi ? hi : v); }
template <class T> SM_HD T sqr(T v) { return v * v; }

template <class T> struct Vec3 {
  T x, y, z;
  SM_HD Vec3 operator+(const Vec3 &o) const { return {x + o.x, y + o.y, z + o.z}; }
  SM_HD Vec3 operator-(const Vec3 &o) const { return {x - o.x, y - o.y, z - o.z}; }
  SM_HD Vec3 operator-() const { return {-x, -y, -z}; }
  SM_HD Vec3 operator*(T s) const { return {x * s, y * s, z * s}; }
  SM_HD Vec3 &operator+=(const Vec3 &o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  SM_HD Vec3 &operator-=(const Vec3 &o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  SM_HD Vec3 &operator*=(T s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
};
template <class T> SM_HD Vec3<T> operator*(T s, const Vec3<T> &v) { return v * s; }
template <class T> SM_HD T dot(const Vec3<T> &a, const Vec3<T> &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T> SM_HD Vec3<T> cross(const Vec3<T> &a, const Vec3<T> &b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T> SM_HD T norm(const Vec3<T> &a) { return std::sqrt(dot(a, a)); }

}  // namespace spreadmap
