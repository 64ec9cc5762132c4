-- expect: string.dump is not allowed in the sandbox
load(string.dump(function() end))
