// tests/vm/program_test.cpp: the small queries on programs (vm/program.*): every global's
// RenderMan name and size, outputs found by name, which programs take derivatives, and the
// identity program of an undisplaced surface, which must verify and give back P and N.
#include <catch2/catch.hpp>

#include <string>

#include "vm/interpreter.h"
#include "vm/program.h"
#include "vm/verify.h"

using namespace affray;
using vm::Global;

TEST_CASE("program: the globals' names and sizes", "[vm][program]") {
    const std::pair<Global, const char*> triples[] = {
        {Global::P, "P"},       {Global::N, "N"},       {Global::Ng, "Ng"}, {Global::I, "I"},  {Global::E, "E"},
        {Global::dPdu, "dPdu"}, {Global::dPdv, "dPdv"}, {Global::Cs, "Cs"}, {Global::Os, "Os"}};
    const std::pair<Global, const char*> floats[] = {
        {Global::s, "s"},   {Global::t, "t"},   {Global::u, "u"},       {Global::v, "v"},
        {Global::du, "du"}, {Global::dv, "dv"}, {Global::time, "time"}, {Global::dtime, "dtime"}};
    for (const auto& [g, name] : triples) {
        CHECK(std::string(vm::GlobalName(g)) == name);
        CHECK(vm::GlobalSize(g) == 3);
    }
    for (const auto& [g, name] : floats) {
        CHECK(std::string(vm::GlobalName(g)) == name);
        CHECK(vm::GlobalSize(g) == 1);
    }
    CHECK(vm::kGlobalCount == 18);
}

TEST_CASE("program: outputs by name, and whether it takes derivatives", "[vm][program]") {
    vm::Program p;
    CHECK_FALSE(p.readsGlobal(Global::P));  // a new program reads nothing
    CHECK(p.findOutput("P") == nullptr);
    p.outputs.push_back({"P", 3, {0, 1, 2}});
    p.outputs.push_back({"h", 1, {3, vm::kNoRegister, vm::kNoRegister}});
    REQUIRE(p.findOutput("h") != nullptr);
    CHECK(p.findOutput("h") == &p.outputs[1]);
    CHECK(p.findOutput("P") == &p.outputs[0]);
    CHECK(p.findOutput("N") == nullptr);
    CHECK(p.findOutput("p") == nullptr);

    p.code = {vm::Instr{vm::Op::Sin, 0, 1, 0, 0}, vm::Instr{vm::Op::Select, 0, 0, 0, 0},
              vm::Instr{vm::Op::Ext, 0, 0, 0, 0}};
    CHECK_FALSE(p.usesDerivatives());
    for (vm::Op derivative : {vm::Op::DerivU, vm::Op::DerivV}) {
        vm::Program q = p;
        q.code.push_back(vm::Instr{derivative, 0, 1, 0, 0});
        CHECK(q.usesDerivatives());
    }
}

TEST_CASE("program: the identity program gives back P and N", "[vm][program]") {
    const vm::Program p = vm::IdentityProgram();
    std::string error;
    REQUIRE(vm::Verify(p, &error));
    CHECK(p.code.empty());
    CHECK(p.readsGlobal(Global::P));
    CHECK(p.readsGlobal(Global::N));
    CHECK_FALSE(p.readsGlobal(Global::u));
    CHECK_FALSE(p.usesDerivatives());
    vm::Interpreter<double> interp(p);
    interp.SetGlobal(Global::P, vm::Vec3<double>(1, 2, 3));
    interp.SetGlobal(Global::N, vm::Vec3<double>(0, 0.6, 0.8));
    interp.Run();
    const vm::Vec3<double> P = interp.OutputTriple(*p.findOutput("P"));
    const vm::Vec3<double> N = interp.OutputTriple(*p.findOutput("N"));
    CHECK((P.x == 1 && P.y == 2 && P.z == 3));
    CHECK((N.x == 0 && N.y == 0.6 && N.z == 0.8));
}
