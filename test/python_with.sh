# Sourced by the test scripts: python_with MODULE... prints the first Python (python3, then
# the system's) that imports every MODULE, and fails if none does. The pyenv or virtualenv
# python3 found first on a developer's PATH often lacks the Debian packages the tests use.
python_with() {
  local imports candidate
  imports=$(IFS=,; echo "$*")
  for candidate in python3 /usr/bin/python3; do
    if "$candidate" -c "import $imports" 2>/dev/null; then
      echo "$candidate"
      return 0
    fi
  done
  return 1
}
