# Shared by the batch and diff test scripts (sourced): a scratch folder removed on exit with its
# own hierarchy cache, pass/fail counting, JSON queries and schema checks.
#   ok / bad MESSAGE            count a check
#   field FILE EXPR             print EXPR evaluated by Python with r = the JSON in FILE
#   validate JSON SCHEMA        check JSON against a JSON schema (python3-jsonschema)
#   finish NAME                 print the counts; the script's exit status says whether all passed
work=$(mktemp -d)
trap 'pkill -9 -f "$work/" 2>/dev/null; rm -rf "$work"' EXIT
export QF_CACHE=$work/cache
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
field() { /usr/bin/python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); print(eval(sys.argv[2]))' "$1" "$2"; }
validate() {
  /usr/bin/python3 -c 'import json, sys, jsonschema
jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))' "$1" "$2" 2>"$work/verr" && ok ||
    bad "$1 does not match $(basename "$2"): $(tail -3 "$work/verr")"
}
finish() {
  echo "$1: $pass passed, $fail failed"
  [[ $fail -eq 0 ]]
}
