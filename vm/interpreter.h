// vm/interpreter.h: the one interpreter, templated on the number type.
// The same program runs as plain doubles (a point), Interval or Affine (a bound over a region of
// the surface) and Dual (exact derivatives for normals): only the number type differs, never the
// loop. Explicit instantiations live in interpreter_<type>.cpp, all from interpreter.inl.
#pragma once

#include <vector>

#include "vm/number.h"
#include "vm/program.h"
#include "vm/vec3.h"

namespace affray::vm {

template <class T>
class Interpreter {
  public:
    /// `program` must have passed Verify() and must outlive the interpreter.
    explicit Interpreter(const Program& program);

    const Program& program() const { return *m_program; }

    /// Sets a global the program reads; a global it does not read is ignored (cheaply), so
    /// callers may set everything or ask program().readsGlobal() first to skip computing it.
    void SetGlobal(Global g, const T& value);
    void SetGlobal(Global g, const Vec3<T>& value);

    /// Sets parameter `index` of program().params (size values) for the following runs; until
    /// then a parameter has its default. Specialised programs have no parameters.
    void SetParam(size_t index, const std::vector<double>& values);

    /// Runs the program once over the current globals and parameters.
    void Run();

    /// The value of an output after Run(); the output must exist.
    Vec3<T> OutputTriple(const ProgramOutput& out) const;
    const T& Register(int r) const { return m_registers[r]; }

  private:
    const Program* m_program;
    std::vector<T> m_registers;
    std::vector<std::vector<double>> m_paramValues;
};

extern template class Interpreter<double>;
extern template class Interpreter<Interval>;
extern template class Interpreter<Affine>;
extern template class Interpreter<Dual<double>>;
extern template class Interpreter<Dual<Affine>>;
extern template class Interpreter<Dual<Interval>>;

}  // namespace affray::vm
