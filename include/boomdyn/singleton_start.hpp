// How a process started without mpiexec (an Open MPI "singleton") starts
// and ends: construct one SingletonStart before PetscInitialize and let it go
// after PetscFinalize (src/app/singleton_start.cpp).
#pragma once

#include <string>

namespace boomdyn {

class SingletonStart {
public:
  SingletonStart();  // sets the environment before MPI_Init
  ~SingletonStart(); // removes the private session directory base, if any
  SingletonStart(const SingletonStart &) = delete;
  SingletonStart &operator=(const SingletonStart &) = delete;

  // The private base of Open MPI's session directories (empty: none made).
  const std::string &sessionBase() const { return sessionBase_; }

private:
  std::string sessionBase_;
};

} // namespace boomdyn
