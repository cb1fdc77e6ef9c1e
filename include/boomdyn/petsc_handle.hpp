// Ownership of one PETSc object: destroyed when the handle goes out of
// scope, also when an error or exception unwinds the scope, so classes that
// hold PETSc objects need no hand-written destructor. Move-only.
//
//   PetscHandle<Vec> x;
//   PetscCall(VecDuplicate(layout, x.address()));
//   PetscCall(VecSet(x, 0.0));              // converts to Vec
#pragma once

#include <petscksp.h>
#include <petscvec.h>

#include <utility>

namespace boomdyn {

// The destroy function of each PETSc type held by a handle. (VecScatter is
// PetscSF in PETSc >= 3.15, so one specialization serves both.)
template <class T>
struct PetscDestroyer;
template <>
struct PetscDestroyer<Vec> {
  static PetscErrorCode destroy(Vec *v) { return VecDestroy(v); }
};
template <>
struct PetscDestroyer<Mat> {
  static PetscErrorCode destroy(Mat *m) { return MatDestroy(m); }
};
template <>
struct PetscDestroyer<IS> {
  static PetscErrorCode destroy(IS *is) { return ISDestroy(is); }
};
template <>
struct PetscDestroyer<VecScatter> {
  static PetscErrorCode destroy(VecScatter *s) { return VecScatterDestroy(s); }
};
template <>
struct PetscDestroyer<KSP> {
  static PetscErrorCode destroy(KSP *k) { return KSPDestroy(k); }
};

template <class T>
class PetscHandle {
public:
  PetscHandle() = default;
  ~PetscHandle() { reset(); }
  PetscHandle(const PetscHandle &) = delete;
  PetscHandle &operator=(const PetscHandle &) = delete;
  PetscHandle(PetscHandle &&other) noexcept : object_(std::exchange(other.object_, nullptr)) {}
  PetscHandle &operator=(PetscHandle &&other) noexcept
  {
    if (this != &other) reset(), object_ = std::exchange(other.object_, nullptr);
    return *this;
  }

  operator T() const { return object_; }
  T get() const { return object_; }
  // For PETSc's creation functions (VecDuplicate(x, h.address())); an object
  // already held is destroyed first.
  T *address()
  {
    reset();
    return &object_;
  }
  // Destruction errors cannot be reported from a destructor; PETSc's own
  // destroy functions fail only on corrupted objects.
  void reset() { (void)PetscDestroyer<T>::destroy(&object_); }

private:
  T object_ = nullptr;
};

} // namespace boomdyn
