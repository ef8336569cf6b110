// The Allrun script of a generated case: `./Allrun [-np N]` meshes, checks and runs it by hand, a
// fresh start only (it refuses a directory holding an earlier run's results, a bad -np and extra
// arguments). A case under [case.tailwater] control = "hold_toe" gets a script that refuses to run:
// only `hydrojump vof` drives the tailgate control.
#include <map>
#include <sstream>

#include "reference/case_parts.hpp"

namespace hydrojump::reference::detail {

namespace {

// interFoam alone would run the outlet at the fixed Umean = q/y2, the set-up the control exists to
// replace (the jump drifts or swings, reference/README.md): refused, with the way to run it.
void write_hold_toe_refusal(std::ostringstream& s, const MeshPlan& plan) {
  s << "# [case.tailwater] control = \"hold_toe\": the outlet's Umean is set between legs of the run by\n"
    << "# `hydrojump vof DIR [--np N]` (reference/tailwater_control.hpp); interFoam alone cannot do that,\n"
    << "# so this case is not run by hand. Mesh: " << cases::option_name(plan.strategy) << ", " << plan.cell_count() << " cells.\n"
    << "echo \"Allrun: this case holds its jump's toe with the tailgate ([case.tailwater] control = \\\"hold_toe\\\"),\"\n"
    << "echo \"which only \\`hydrojump vof <this directory>\\` drives: run it that way, or regenerate it with\"\n"
    << "echo \"control = \\\"fixed_depth\\\" to run it by hand at the fixed outlet velocity\"\n"
    << "exit 1\n";
}

// The options (-np N) and the fresh-start guard, and the `run` function of the script.
void write_allrun_preamble(std::ostringstream& s, const MeshPlan& plan) {
  s << "# Run by hand:   ./Allrun            (serial)\n"
    << "#                ./Allrun -np 4      (MPI: decomposePar, mpirun, reconstructPar)\n"
    << "# or with `hydrojump vof DIR [--np N]`, which adds checks, progress, divergence detection and\n"
    << "# resuming. Mesh: " << cases::option_name(plan.strategy) << ", " << plan.cell_count() << " cells.\n"
    << "case \"$0\" in */*) cd \"${0%/*}\" || exit 1 ;; esac\n"
    << "export WM_PROJECT_DIR=\"${WM_PROJECT_DIR:-/usr/share/openfoam}\"\n"
    << "np=1\n"
    << "case \"$#:$1\" in\n"
    << "    0:) ;;\n"
    << "    2:-np) np=\"$2\"\n"
    << "         case \"$np\" in\n"
    << "             \"\"|*[!0-9]*) echo \"Allrun: -np needs a whole number of MPI ranks, 1 or more (got '$np')\"; exit 1 ;;\n"
    << "         esac\n"
    << "         [ \"$np\" -ge 1 ] || { echo \"Allrun: -np needs a whole number of MPI ranks, 1 or more (got '$np')\"; exit 1; } ;;\n"
    << "    *) echo \"usage: ./Allrun [-np N]\"; exit 1 ;;\n"
    << "esac\n";
  s << "# A fresh start only: controlDict starts from the latest time, so the results of an earlier run\n"
    << "# would be continued (or met by a new mesh they do not fit).\n"
    << "for d in *; do\n"
    << "    case \"$d\" in\n"
    << "        0|0.orig) ;;\n"
    << "        [0-9]*|processor*|postProcessing)\n"
    << "            echo \"Allrun: this directory holds the results of an earlier run ($d); remove them first\"\n"
    << "            echo \"(foamListTimes -rm; rm -rf processor* postProcessing) or continue that run with\"\n"
    << "            echo \"\\`hydrojump vof <this directory> --resume\\`\"\n"
    << "            exit 1 ;;\n"
    << "    esac\n"
    << "done\n"
    << "# run LOG APPLICATION [ARGUMENTS]: stops at the first failure with the end of its log\n"
    << "run() {\n"
    << "    log=\"$1\"; app=\"$2\"; shift 2\n"
    << "    echo \"Running $app $*\"\n"
    << "    \"$app\" \"$@\" > \"$log\" 2>&1 || { echo \"$app failed: see $log\"; tail -n 20 \"$log\"; exit 1; }\n"
    << "}\n";
}

// The mesh steps, checkMesh, setFields and interFoam, serial or with MPI.
void write_allrun_steps(std::ostringstream& s, const VofCase& vof) {
  std::map<std::string, int> used;
  for (const FoamStep& step : vof.mesh_steps) {
    const int k = used[step.application]++;
    const std::string suffix = k > 0 ? std::string(".").append(std::to_string(k + 1)) : std::string();
    s << "run log." << step.application << suffix << ' ' << step.application;
    for (const std::string& a : step.arguments) s << ' ' << a;
    s << '\n';
  }
  s << "run log.checkMesh checkMesh\n"
    << "grep -q \"Mesh OK.\" log.checkMesh || { echo \"checkMesh found a bad mesh: see log.checkMesh\"; exit 1; }\n"
    << "{ rm -rf 0 && cp -r 0.orig 0; } || { echo \"Allrun: cannot copy 0.orig to 0\"; exit 1; }\n"
    << "run log.setFields setFields\n"
    << "if [ \"$np\" -gt 1 ]; then\n"
    << "    run log.foamDictionary.ranks foamDictionary -entry numberOfSubdomains -set \"$np\" system/decomposeParDict\n"
    << "    run log.foamDictionary.split foamDictionary -entry coeffs/n -set \"($np 1 1)\" system/decomposeParDict\n"
    << "    run log.decomposePar decomposePar -force\n"
    << "    root=\"\"; [ \"$(id -u)\" = 0 ] && root=\"--allow-run-as-root\"\n"
    << "    echo \"Running mpirun -np $np interFoam -parallel\"\n"
    << "    # --oversubscribe: Open MPI refuses more ranks than cores without it, and it is harmless otherwise\n"
    << "    mpirun $root --oversubscribe -np \"$np\" -x WM_PROJECT_DIR interFoam -parallel > log.interFoam 2>&1 || "
       "{ echo \"interFoam failed: see log.interFoam\"; tail -n 20 log.interFoam; exit 1; }\n"
    << "    run log.reconstructPar reconstructPar\n"
    << "else\n"
    << "    run log.interFoam interFoam\n"
    << "fi\n";
}

}  // namespace

std::string allrun_script(const VofCase& vof, const CaseInputs& in) {
  std::ostringstream s;
  s << "#!/bin/sh\n"
    << "# OpenFOAM interFoam case written by hydrojump from " << in.provenance << ".\n";
  if (in.c.holds_toe()) {
    write_hold_toe_refusal(s, in.plan);
  } else {
    write_allrun_preamble(s, in.plan);
    write_allrun_steps(s, vof);
  }
  return s.str();
}

}  // namespace hydrojump::reference::detail
